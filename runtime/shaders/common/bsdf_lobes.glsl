// The BSDF lobes of Cycles 3.4's BSDF nodes other than the Principled BSDF
// (MaterialOutputs::lobeWeight, nodes/bsdf.inc; docs/design/closures.md), in a local frame
// where the shading normal is +z and wo.z > 0. Each lobe's `evaluate` is f(wo, wi) |wi.z|
// per unit weight; its colour and the Mix/Add Shader weights are the lobe's weight. Formulas
// follow intern/cycles/kernel/closure/ (Blender 3.4): bsdf_diffuse.h, bsdf_oren_nayar.h,
// bsdf_microfacet.h, bsdf_microfacet_beckmann.h, bsdf_ashikhmin_velvet.h. The material's
// BSDF is the lobes' sum; sampling picks one lobe with probability proportional to its
// weight's luminance (every lobe's albedo is taken as 1) and the pdf is the mixture's, so
// that light sampling's MIS sees the density that BSDF sampling really has.
// Needs brdf.glsl (kPi, smithG1, ggxD, ggxSampleVisibleNormal) and the prelude (MG_LOBE_*).

#ifdef MG_BSDF_LOBES

// A material's lobes at one hit, with their pick probabilities.
struct BsdfLobes {
  int count;
  vec3 weight[MG_MAX_LOBES];
  int kind[MG_MAX_LOBES];
  float roughness[MG_MAX_LOBES];
  float pick[MG_MAX_LOBES];  // probability that BSDF sampling samples lobe i
};

BsdfLobes bsdfLobesFromMaterial(MaterialOutputs m) {
  BsdfLobes lobes;
  lobes.count = min(m.lobeCount, MG_MAX_LOBES);
  float total = 0.0;
  for (int i = 0; i < MG_MAX_LOBES; ++i) {
    lobes.weight[i] = max(m.lobeWeight[i].rgb, vec3(0.0));
    lobes.kind[i] = int(m.lobeWeight[i].w);
    lobes.roughness[i] = clamp(m.lobeParameters[i].x, 0.0, 1.0);
    lobes.pick[i] = i < lobes.count ? dot(lobes.weight[i], vec3(0.2126, 0.7152, 0.0722)) : 0.0;
    total += lobes.pick[i];
  }
  for (int i = 0; i < MG_MAX_LOBES; ++i) lobes.pick[i] = total > 0.0 ? lobes.pick[i] / total : 0.0;
  return lobes;
}

// The microfacet alpha of Cycles' Glossy BSDF (roughness^2), kept above GGX's float limit
// as brdf.glsl keeps it (roughness 0.02): Cycles takes roughness 0 as a perfect mirror.
float lobeAlpha(float roughness) {
  float r = max(roughness, 0.02);
  return r * r;
}

// Cosine-weighted hemisphere direction.
vec3 sampleCosineHemisphere(vec2 u) {
  float r = sqrt(u.x);
  float phi = 2.0 * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
}

// Oren-Nayar as Cycles computes it (bsdf_oren_nayar_get_intensity, the "improved"
// Oren-Nayar of Fujii): A = 1 / (pi + (3 pi - 4) / 6 sigma), B = sigma A, times n.l.
float orenNayarCos(float sigma, vec3 wo, vec3 wi) {
  float a = 1.0 / (kPi + ((3.0 * kPi - 4.0) / 6.0) * sigma);
  float b = sigma * a;
  float nl = max(wi.z, 0.0);
  float nv = max(wo.z, 0.0);
  float t = dot(wi, wo) - nl * nv;
  if (t > 0.0) t /= max(nl, nv) + 1e-30;
  return nl * (a + b * t);
}

// Beckmann's distribution D(h) (Walter et al. 2007, eq. 25).
float beckmannD(float cosThetaH, float alpha) {
  if (cosThetaH <= 0.0) return 0.0;
  float c2 = cosThetaH * cosThetaH;
  float tan2 = (1.0 - c2) / c2;
  float a2 = alpha * alpha;
  return exp(-tan2 / a2) / (kPi * a2 * c2 * c2);
}

// Beckmann's Smith G1 in Walter et al.'s rational approximation (2007, eq. 27), as Cycles'
// bsdf_beckmann_G1.
float beckmannG1(float cosTheta, float alpha) {
  float c = abs(cosTheta);
  if (c >= 1.0) return 1.0;
  float a = c / (alpha * sqrt(1.0 - c * c));  // 1 / (alpha tan(theta))
  if (a >= 1.6) return 1.0;
  return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

// Ashikhmin's velvet (Ashikhmin, Premoze and Shirley 2000) as Cycles' bsdf_ashikhmin_velvet:
// D = exp(-cot^2 / sigma^2) / (pi sigma^2 sin^4), G = min(1, 2 |n.h / o.h| min(n.o, n.i)).
float velvetCos(float sigma, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  vec3 h = normalize(wo + wi);
  float cosNH = h.z;
  float cosHO = abs(dot(wo, h));
  if (!(abs(cosNH) < 1.0 - 1e-5 && cosHO > 1e-5)) return 0.0;
  float invSigma2 = 1.0 / (sigma * sigma);
  float ratio = max(cosNH / cosHO, 1e-5);
  float g = min(1.0, min(2.0 * abs(ratio * wo.z), 2.0 * abs(ratio * wi.z)));
  float sin2 = 1.0 - cosNH * cosNH;
  float d = exp(-(cosNH * cosNH / sin2) * invSigma2) * invSigma2 / (kPi * sin2 * sin2);
  return 0.25 * d * g / wo.z;
}

// f(wo, wi) |wi.z| of one lobe per unit weight.
float lobeEvaluateCos(int kind, float roughness, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;  // every lobe here reflects
  if (kind == MG_LOBE_DIFFUSE)
    return roughness > 0.0 ? orenNayarCos(roughness, wo, wi) : wi.z / kPi;
  if (kind == MG_LOBE_VELVET) return velvetCos(max(roughness, 0.01), wo, wi);
  vec3 h = normalize(wo + wi);
  float alpha = lobeAlpha(roughness);
  // Microfacet reflection without Fresnel: D G / (4 n.o), G = G1(o) G1(i) (Cycles'
  // separable Smith term).
  if (kind == MG_LOBE_GLOSSY_BECKMANN)
    return beckmannD(h.z, alpha) * beckmannG1(wo.z, alpha) * beckmannG1(wi.z, alpha) /
           (4.0 * wo.z);
  return ggxD(h.z, alpha) * smithG1(wo.z, alpha) * smithG1(wi.z, alpha) / (4.0 * wo.z);
}

// The density with which lobeSample draws wi.
float lobePdf(int kind, float roughness, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  if (kind == MG_LOBE_DIFFUSE || kind == MG_LOBE_VELVET) return wi.z / kPi;
  vec3 h = normalize(wo + wi);
  float alpha = lobeAlpha(roughness);
  if (kind == MG_LOBE_GLOSSY_BECKMANN)  // D(h) n.h over the reflection's Jacobian 4 o.h
    return beckmannD(h.z, alpha) * h.z / (4.0 * max(dot(wo, h), 1e-8));
  return smithG1(wo.z, alpha) * ggxD(h.z, alpha) / (4.0 * wo.z);  // visible normals
}

// A direction drawn from one lobe: cosine-weighted for the diffuse ones, GGX's visible
// normals (Heitz 2018), Beckmann's D(h) n.h (Walter et al. 2007, eq. 28-29).
vec3 lobeSample(int kind, float roughness, vec3 wo, vec2 u) {
  if (kind == MG_LOBE_DIFFUSE || kind == MG_LOBE_VELVET) return sampleCosineHemisphere(u);
  float alpha = lobeAlpha(roughness);
  vec3 h;
  if (kind == MG_LOBE_GLOSSY_BECKMANN) {
    float tan2 = -alpha * alpha * log(max(1.0 - u.x, 1e-12));
    float cosTheta = inversesqrt(1.0 + tan2);
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    float phi = 2.0 * kPi * u.y;
    h = vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
  } else {
    h = ggxSampleVisibleNormal(wo, alpha, u);
  }
  return reflect(-wo, h);
}

// The material's f(wo, wi) |wi.z|: every lobe's, weighted.
vec3 bsdfLobesEvaluateCos(BsdfLobes lobes, vec3 wo, vec3 wi) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < lobes.count; ++i)
    sum += lobes.weight[i] * lobeEvaluateCos(lobes.kind[i], lobes.roughness[i], wo, wi);
  return sum;
}

// The density of bsdfLobesSample: the lobes' densities mixed by their pick probabilities.
float bsdfLobesPdf(BsdfLobes lobes, vec3 wo, vec3 wi) {
  float pdf = 0.0;
  for (int i = 0; i < lobes.count; ++i)
    if (lobes.pick[i] > 0.0)
      pdf += lobes.pick[i] * lobePdf(lobes.kind[i], lobes.roughness[i], wo, wi);
  return pdf;
}

// The lobe that uLobe in [0, 1) picks by the pick probabilities (-1: none has weight).
int bsdfLobesPick(BsdfLobes lobes, float uLobe) {
  int picked = -1;
  float cumulative = 0.0;
  for (int i = 0; i < lobes.count; ++i) {
    if (lobes.pick[i] <= 0.0) continue;
    picked = i;  // the last one with weight also takes uLobe's float round-off above the sum
    cumulative += lobes.pick[i];
    if (uLobe < cumulative) break;
  }
  return picked;
}

#endif  // MG_BSDF_LOBES
