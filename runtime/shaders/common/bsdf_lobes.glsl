// The BSDF lobes of Cycles 3.4's BSDF nodes other than the Principled BSDF, and of the
// Principled BSDF v1 with its sheen, clearcoat and transmission layers
// (MaterialOutputs::lobeWeight, nodes/bsdf.inc; docs/design/closures.md), in a local frame
// where the shading normal is +z and wo.z > 0 (wi.z < 0: through the surface). Each lobe's
// `evaluate` is f(wo, wi) |wi.z| per unit weight; its colour and the Mix/Add Shader weights
// are the lobe's weight. Formulas follow intern/cycles/kernel/closure/ (Blender 3.4):
// bsdf_diffuse.h, bsdf_oren_nayar.h, bsdf_microfacet.h, bsdf_microfacet_beckmann.h,
// bsdf_ashikhmin_velvet.h, bsdf_refraction.h, bsdf_transparent.h, bsdf_translucent.h,
// bsdf_principled_sheen.h; the Principled lobe is brdf.glsl's BRDF of the material's
// Principled outputs, the Principled transmission a Glass lobe with svm/closure.h's
// Principled weights. Singular lobes (Transparent, and Refraction and Glass where Cycles'
// microfacet is a perfect one: alpha^2 <= 1e-7) have no density: they evaluate to 0 (light
// sampling cannot find their direction) and are sampled apart. The material's BSDF is the
// lobes' sum; sampling picks one lobe with probability proportional to its weight's
// luminance (every lobe's albedo is taken as 1) and the pdf is the mixture's, so that light
// sampling's MIS sees the density that BSDF sampling really has.
// Needs brdf.glsl (kPi, smithG1, ggxD, ggxSampleVisibleNormal) and the prelude (MG_LOBE_*).

#ifdef MG_BSDF_LOBES

// A material's lobes at one hit, with their pick probabilities. Every loop over them runs
// over all MG_MAX_LOBES slots (a slot past `count` has pick 0 and is skipped), a constant trip
// count that a GPU's compiler unrolls, and the sampled lobe is copied out once by bsdfLobeAt:
// an array read with a dynamic index is kept in local memory instead of registers (on an
// H100 this took the Blender scene's shade pass from 256 to 160 B of it; docs/results.md).
struct BsdfLobes {
  int count;
  vec3 weight[MG_MAX_LOBES];
  int kind[MG_MAX_LOBES];
  float roughness[MG_MAX_LOBES];
  float eta[MG_MAX_LOBES];   // relative IOR across the surface: the far side's over the ray's
  float pick[MG_MAX_LOBES];  // probability that BSDF sampling samples lobe i
#ifdef MG_PRINCIPLED_LAYERS
  // Only in scenes with a PrincipledLayers node (the host's MG_PRINCIPLED_LAYERS): the
  // Principled BRDF and glass in the lobe loops cost the other scenes' shade pass registers
  // (H100, the Blender material scene: 8.9 against 10.1 ms a frame).
  BrdfParameters principled;  // the MG_LOBE_PRINCIPLED lobe's BRDF (per unit weight)
  // The MG_LOBE_PRINCIPLED_GLASS lobe's refraction tint (the base colour), its reflection's F0
  // colour (Cycles' cspec0: white mixed by the specular tint towards the base colour) and
  // its reflection's roughness (the material's; the lobe's own roughness is the refraction's).
  vec3 glassRefractionColor;
  vec3 glassReflectionF0;
  float glassReflectionRoughness;
#endif
#ifdef MG_LOBE_NORMALS
  // Only in scenes with a lobe shaded about its own normal (a BSDF node's Normal, the
  // Principled's Clearcoat Normal: the host's MG_LOBE_NORMALS; bsdfLobesSetNormals). toLobe[i]
  // turns a direction of the material's frame into lobe i's (its normal +z) where ownNormal[i];
  // with any own normal, each lobe checks its directions against the geometric normal
  // (geometricNormal, in the material's frame) itself, as Cycles' closures do.
  bool anyOwnNormal;
  bool ownNormal[MG_MAX_LOBES];
  mat3 toLobe[MG_MAX_LOBES];
  vec3 geometricNormal;
#endif
};

// `entering`: the ray hit the front face (by the geometric normal), so a transmission lobe's
// relative IOR is its IOR, else 1 / IOR (Cycles' svm_node_closure_bsdf: SD_BACKFACING).
// `principled`: the BRDF of the material's Principled outputs, which a MG_LOBE_PRINCIPLED lobe
// weights.
BsdfLobes bsdfLobesFromMaterial(MaterialOutputs m, bool entering, BrdfParameters principled) {
  BsdfLobes lobes;
#ifdef MG_PRINCIPLED_LAYERS
  lobes.principled = principled;
  vec3 baseColor = clamp(m.baseColor, 0.0, 1.0);
  lobes.glassRefractionColor = max(m.baseColor, vec3(0.0));
  float tint = clamp(m.specularTint, 0.0, 1.0);
  lobes.glassReflectionF0 = baseColor * tint + vec3(1.0 - tint);
  lobes.glassReflectionRoughness = clamp(m.roughness, 0.0, 1.0);
#endif
  lobes.count = min(m.lobeCount, MG_MAX_LOBES);
  float total = 0.0;
  for (int i = 0; i < MG_MAX_LOBES; ++i) {
    lobes.weight[i] = max(m.lobeWeight[i].rgb, vec3(0.0));
    lobes.kind[i] = int(m.lobeWeight[i].w);
    lobes.roughness[i] = clamp(m.lobeParameters[i].x, 0.0, 1.0);
#ifdef MG_PRINCIPLED_LAYERS
    if (lobes.kind[i] == MG_LOBE_PRINCIPLED) {
      // Its roughness (ray cones, Light Path) is its BRDF's; its IOR slot holds the diffuse's
      // share of its weight (the transmission takes the rest: PrincipledLayers).
      lobes.roughness[i] = principled.roughness;
      float diffuseShare = max(m.lobeParameters[i].y, 0.0);
      lobes.principled.diffuse *= diffuseShare;
      lobes.principled.diffuseBurley *= diffuseShare;
    }
#endif
    float ior = max(m.lobeParameters[i].y, 1e-5);
    lobes.eta[i] = entering ? ior : 1.0 / ior;
    lobes.pick[i] = i < lobes.count ? dot(lobes.weight[i], vec3(0.2126, 0.7152, 0.0722)) : 0.0;
    total += lobes.pick[i];
  }
  for (int i = 0; i < MG_MAX_LOBES; ++i)
    lobes.pick[i] = total > 0.0 ? lobes.pick[i] / total : 0.0;
  return lobes;
}

#ifdef MG_LOBE_NORMALS
// A lobe's own world-space normal from its lobeParameters z, w (the node library's
// mg_encodeLobeNormal: z = 2 + the octahedral x, w the octahedral y; Cigolle et al. 2014).
vec3 lobeNormalDecode(vec2 code) {
  vec2 e = vec2(code.x - 2.0, code.y);
  vec3 v = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (v.z < 0.0)
    v.xy = (vec2(1.0) - abs(v.yx)) * vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0);
  return normalize(v);
}

// Whether lobe i has its own normal (lobeParameters z >= 1; 0 is the material's).
bool lobeHasOwnNormal(MaterialOutputs m, int i) {
  return m.lobeParameters[i].z >= 1.0;
}

// Lobe i's view of wo and wi (the material's frame): in its own frame where it has its own
// normal. False: wi lies on one side of the lobe's normal and the other of the geometric
// normal (a direction between the two planes, which would leak light through the surface or
// hide it: path_shading.glsl's sameSideOfBothNormals, lobe by lobe; Cycles 3.4 evaluates a
// closure's reflection only above Ng and its transmission only below, bsdf.h bsdf_eval).
// lobeFrameDirections takes the lobe's frame itself (its ownNormal and toLobe), as the
// sampled lobe's copy (bsdfLobeAt) holds them.
bool lobeFrameDirections(BsdfLobes lobes, bool ownNormal, mat3 toLobe, vec3 wo, vec3 wi,
                         out vec3 woLobe, out vec3 wiLobe) {
  woLobe = wo;
  wiLobe = wi;
  if (!lobes.anyOwnNormal) return true;
  if (ownNormal) {
    woLobe = toLobe * wo;
    wiLobe = toLobe * wi;
  }
  float g = dot(wi, lobes.geometricNormal);
  return wiLobe.z > 0.0 ? g > 0.0 : g < 0.0;
}
bool lobeDirections(BsdfLobes lobes, int i, vec3 wo, vec3 wi, out vec3 woLobe,
                    out vec3 wiLobe) {
  return lobeFrameDirections(lobes, lobes.ownNormal[i], lobes.toLobe[i], wo, wi, woLobe,
                             wiLobe);
}
#else
// Without per-lobe normals every lobe sees the material's frame.
bool lobeDirections(BsdfLobes lobes, int i, vec3 wo, vec3 wi, out vec3 woLobe,
                    out vec3 wiLobe) {
  woLobe = wo;
  wiLobe = wi;
  return true;
}
#endif

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

// Cycles 3.4's Principled sheen (bsdf_principled_sheen.h, Burley 2012's sheen): f |wi.z| =
// (1 - wi.h)^5 wi.z, no 1/pi, on the view's side only.
float principledSheenCos(vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  vec3 h = normalize(wo + wi);
  float m = clamp(1.0 - dot(wi, h), 0.0, 1.0);
  float m2 = m * m;
  return m2 * m2 * m * wi.z;
}

// Berry's distribution (Burley 2012's GTR1) of alpha^2 = alpha2, as Cycles' microfacet_GTR1_D:
// (alpha^2 - 1) / (pi ln(alpha^2) (1 + (alpha^2 - 1) cos^2)), normalised so that its
// projected area is 1.
float gtr1D(float cosThetaH, float alpha2) {
  if (alpha2 >= 1.0) return 1.0 / kPi;
  float t = 1.0 + (alpha2 - 1.0) * cosThetaH * cosThetaH;
  return (alpha2 - 1.0) / (kPi * log(alpha2) * t);
}

// A GTR1 normal drawn with density D(h) cos(theta_h) (Burley 2012, appendix B).
vec3 gtr1SampleNormal(float alpha2, vec2 u) {
  float cos2 = alpha2 >= 1.0 ? 1.0 - u.x : (1.0 - pow(alpha2, 1.0 - u.x)) / (1.0 - alpha2);
  float cosTheta = sqrt(clamp(cos2, 0.0, 1.0));
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * kPi * u.y;
  return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// Smith's GGX Lambda (Heitz 2014, eq. 72): G1 = 1 / (1 + Lambda).
float ggxLambda(float cosTheta, float alpha) {
  float c2 = cosTheta * cosTheta;
  float tan2 = max(1.0 - c2, 0.0) / max(c2, 1e-12);
  return 0.5 * (sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

// Cycles 3.4's Principled clearcoat (bsdf_microfacet.h, the GGX clearcoat closure):
// f |wi.z| = F D G / (4 wo.z) with D GTR1 of alpha = roughness^2 (clamped as lobeAlpha), the
// height-correlated GGX shadowing G = 1 / (1 + Lambda(o) + Lambda(i)) of Cycles' fixed alpha
// 0.25, and F the dielectric Fresnel of IOR 1.5 at wi.h (Cycles' interpolate_fresnel_color of
// cspec0 0.04, which is that Fresnel's own value at normal incidence).
const float kClearcoatShadowingAlpha = 0.25;
const float kClearcoatIor = 1.5;
float principledClearcoatCos(float roughness, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  vec3 h = normalize(wo + wi);
  float alpha = lobeAlpha(roughness);
  float g = 1.0 / (1.0 + ggxLambda(wo.z, kClearcoatShadowingAlpha) +
                   ggxLambda(wi.z, kClearcoatShadowingAlpha));
  return fresnelDielectric(dot(wi, h), kClearcoatIor) * gtr1D(h.z, alpha * alpha) * g /
         (4.0 * wo.z);
}
// The density of the clearcoat's sampling: a GTR1 normal reflected, D cos(theta_h) / (4 o.h).
float principledClearcoatPdf(float roughness, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  vec3 h = normalize(wo + wi);
  float alpha = lobeAlpha(roughness);
  return gtr1D(h.z, alpha * alpha) * h.z / (4.0 * max(dot(wo, h), 1e-8));
}

bool lobeIsRefraction(int kind) {
  return kind == MG_LOBE_REFRACTION_GGX || kind == MG_LOBE_REFRACTION_BECKMANN;
}
bool lobeIsGlass(int kind) {
  return kind == MG_LOBE_GLASS_GGX || kind == MG_LOBE_GLASS_BECKMANN;
}
bool lobeIsBeckmann(int kind) {
  return kind == MG_LOBE_GLOSSY_BECKMANN || kind == MG_LOBE_REFRACTION_BECKMANN ||
         kind == MG_LOBE_GLASS_BECKMANN;
}
// Whether a lobe sends light through the surface (its directions may have wi.z < 0).
bool lobeTransmits(int kind) {
  return kind == MG_LOBE_TRANSLUCENT || kind == MG_LOBE_TRANSPARENT || lobeIsRefraction(kind) ||
         lobeIsGlass(kind) || kind == MG_LOBE_PRINCIPLED_GLASS;
}

// A lobe without density: Transparent, and a Glossy, Refraction or Glass lobe where Cycles
// takes the microfacet as perfectly smooth (alpha_x alpha_y <= 1e-7, bsdf_microfacet.h;
// alpha = roughness^2): a Glossy of Roughness 0 is a mirror, which light sampling cannot see.
// The Principled lobe keeps brdf.glsl's clamp (0.02).
bool lobeIsSingular(int kind, float roughness) {
  if (kind == MG_LOBE_TRANSPARENT) return true;
  float alpha = roughness * roughness;
  return (kind == MG_LOBE_GLOSSY_GGX || kind == MG_LOBE_GLOSSY_BECKMANN ||
          lobeIsRefraction(kind) || lobeIsGlass(kind) || kind == MG_LOBE_PRINCIPLED_GLASS) &&
         alpha * alpha <= 1e-7;
}

float microfacetD(bool beckmann, float cosThetaH, float alpha) {
  return beckmann ? beckmannD(cosThetaH, alpha) : ggxD(cosThetaH, alpha);
}
float microfacetG1(bool beckmann, float cosTheta, float alpha) {
  return beckmann ? beckmannG1(cosTheta, alpha) : smithG1(cosTheta, alpha);
}

// The density of the microfacet normal h that lobeSample draws: GGX's visible normals
// G1(o) D(h) o.h / n.o (Heitz 2018), Beckmann's D(h) n.h (Walter et al. 2007, eq. 28).
float microfacetNormalPdf(bool beckmann, vec3 wo, vec3 h, float alpha) {
  if (beckmann) return beckmannD(h.z, alpha) * h.z;
  return smithG1(wo.z, alpha) * ggxD(h.z, alpha) * max(dot(wo, h), 0.0) / wo.z;
}

vec3 microfacetSampleNormal(bool beckmann, vec3 wo, float alpha, vec2 u) {
  if (!beckmann) return ggxSampleVisibleNormal(wo, alpha, u);
  float tan2 = -alpha * alpha * log(max(1.0 - u.x, 1e-12));
  float cosTheta = inversesqrt(1.0 + tan2);
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * kPi * u.y;
  return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// Microfacet reflection without Fresnel, f |wi.z| = D G1(o) G1(i) / (4 n.o) (Cycles'
// separable Smith term), and its density (the normal's over the reflection's 4 o.h).
float microfacetReflectionCos(bool beckmann, float alpha, vec3 wo, vec3 wi) {
  if (wi.z <= 0.0) return 0.0;
  vec3 h = normalize(wo + wi);
  return microfacetD(beckmann, h.z, alpha) * microfacetG1(beckmann, wo.z, alpha) *
         microfacetG1(beckmann, wi.z, alpha) / (4.0 * wo.z);
}
float microfacetReflectionPdf(bool beckmann, float alpha, vec3 wo, vec3 wi) {
  if (wi.z <= 0.0) return 0.0;
  vec3 h = normalize(wo + wi);
  return microfacetNormalPdf(beckmann, wo, h, alpha) / (4.0 * max(dot(wo, h), 1e-8));
}

// The refraction half vector of wo (on the ray's side) and wi (through, relative IOR eta):
// h ~ wo + eta wi, turned to the normal's side (Walter et al. 2007, eq. 16). False: wo and
// wi are not on opposite sides of it, so no microfacet refracts one into the other.
bool refractionHalfVector(vec3 wo, vec3 wi, float eta, out vec3 h) {
  h = wo + eta * wi;
  if (!(dot(h, h) > 1e-20)) return false;
  h = normalize(h);
  if (h.z < 0.0) h = -h;
  return dot(wo, h) > 0.0 && dot(wi, h) < 0.0;
}

// Microfacet refraction without Fresnel (Walter et al. 2007, eq. 21, as Cycles 3.4's
// bsdf_microfacet_ggx_eval_transmit): f |wi.z| = D G1(o) G1(i) |o.h| |i.h| eta^2 /
// (n.o (o.h + eta i.h)^2); its density is the normal's times the Jacobian eta^2 |i.h| /
// (o.h + eta i.h)^2 (eq. 17), so that f |wi.z| / pdf = G1(i): no eta^2 radiance scaling, as
// in Cycles.
float microfacetRefractionCos(bool beckmann, float alpha, float eta, vec3 wo, vec3 wi) {
  vec3 h;
  if (wi.z >= 0.0 || !refractionHalfVector(wo, wi, eta, h)) return 0.0;
  float oh = dot(wo, h);
  float ih = dot(wi, h);
  float denominator = oh + eta * ih;
  return microfacetD(beckmann, h.z, alpha) * microfacetG1(beckmann, wo.z, alpha) *
         microfacetG1(beckmann, wi.z, alpha) * oh * abs(ih) * eta * eta /
         (wo.z * denominator * denominator);
}
float microfacetRefractionPdf(bool beckmann, float alpha, float eta, vec3 wo, vec3 wi) {
  vec3 h;
  if (wi.z >= 0.0 || !refractionHalfVector(wo, wi, eta, h)) return 0.0;
  float denominator = dot(wo, h) + eta * dot(wi, h);
  return microfacetNormalPdf(beckmann, wo, h, alpha) * eta * eta * abs(dot(wi, h)) /
         (denominator * denominator);
}

// The direction that refracts wo through a surface of normal m and relative IOR eta; the
// zero vector under total internal reflection (GLSL refract takes the inverse ratio).
vec3 refractDirection(vec3 wo, vec3 m, float eta) {
  return refract(-wo, m, 1.0 / eta);
}

// f(wo, wi) |wi.z| of one lobe per unit weight; 0 for a singular lobe.
float lobeEvaluateCos(int kind, float roughness, float eta, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || lobeIsSingular(kind, roughness)) return 0.0;
  if (kind == MG_LOBE_TRANSLUCENT) return wi.z < 0.0 ? -wi.z / kPi : 0.0;
  bool beckmann = lobeIsBeckmann(kind);
  float alpha = lobeAlpha(roughness);
  if (lobeIsRefraction(kind)) return microfacetRefractionCos(beckmann, alpha, eta, wo, wi);
  if (lobeIsGlass(kind)) {
    // Cycles 3.4 weights the glass's reflection by the Fresnel of the shading normal and
    // its refraction by the rest (svm_node_closure_bsdf, CLOSURE_BSDF_*_GLASS_ID).
    float fresnel = fresnelDielectric(wo.z, eta);
    return wi.z > 0.0 ? fresnel * microfacetReflectionCos(beckmann, alpha, wo, wi)
                      : (1.0 - fresnel) * microfacetRefractionCos(beckmann, alpha, eta, wo, wi);
  }
  if (wi.z <= 0.0) return 0.0;  // the other lobes reflect
  if (kind == MG_LOBE_DIFFUSE)
    return roughness > 0.0 ? orenNayarCos(roughness, wo, wi) : wi.z / kPi;
  if (kind == MG_LOBE_VELVET) return velvetCos(max(roughness, 0.01), wo, wi);
  if (kind == MG_LOBE_PRINCIPLED_SHEEN) return principledSheenCos(wo, wi);
  if (kind == MG_LOBE_PRINCIPLED_CLEARCOAT) return principledClearcoatCos(roughness, wo, wi);
  return microfacetReflectionCos(beckmann, alpha, wo, wi);
}

// The density with which lobeSample draws wi; 0 for a singular lobe.
float lobePdf(int kind, float roughness, float eta, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || lobeIsSingular(kind, roughness)) return 0.0;
  if (kind == MG_LOBE_TRANSLUCENT) return wi.z < 0.0 ? -wi.z / kPi : 0.0;
  bool beckmann = lobeIsBeckmann(kind);
  float alpha = lobeAlpha(roughness);
  if (lobeIsRefraction(kind)) return microfacetRefractionPdf(beckmann, alpha, eta, wo, wi);
  if (lobeIsGlass(kind)) {
    float fresnel = fresnelDielectric(wo.z, eta);  // the probability of reflecting
    return wi.z > 0.0 ? fresnel * microfacetReflectionPdf(beckmann, alpha, wo, wi)
                      : (1.0 - fresnel) * microfacetRefractionPdf(beckmann, alpha, eta, wo, wi);
  }
  if (wi.z <= 0.0) return 0.0;
  if (kind == MG_LOBE_DIFFUSE || kind == MG_LOBE_VELVET || kind == MG_LOBE_PRINCIPLED_SHEEN)
    return wi.z / kPi;
  if (kind == MG_LOBE_PRINCIPLED_CLEARCOAT) return principledClearcoatPdf(roughness, wo, wi);
  return microfacetReflectionPdf(beckmann, alpha, wo, wi);
}

// A direction drawn from one lobe: cosine-weighted for the diffuse ones (on the far side for
// Translucent), a microfacet normal (microfacetSampleNormal) reflected or refracted, the
// Glass lobe reflecting with probability F (uChoice). A singular lobe's direction is exact,
// and `singularWeight` is its f |wi.z| / pdf per unit weight (1 for each of these lobes:
// Cycles' bsdf_refraction, bsdf_transparent and the sharp glass's Fresnel-chosen branch);
// the zero vector: no direction (total internal reflection of a Refraction lobe).
vec3 lobeSample(int kind, float roughness, float eta, vec3 wo, vec2 u, float uChoice,
                out float singularWeight) {
  singularWeight = 1.0;
  if (kind == MG_LOBE_DIFFUSE || kind == MG_LOBE_VELVET || kind == MG_LOBE_PRINCIPLED_SHEEN)
    return sampleCosineHemisphere(u);
  if (kind == MG_LOBE_PRINCIPLED_CLEARCOAT) {
    float alpha = lobeAlpha(roughness);
    return reflect(-wo, gtr1SampleNormal(alpha * alpha, u));
  }
  if (kind == MG_LOBE_TRANSLUCENT) return sampleCosineHemisphere(u) * vec3(1.0, 1.0, -1.0);
  if (kind == MG_LOBE_TRANSPARENT) return -wo;
  vec3 m = vec3(0.0, 0.0, 1.0);
  if (!lobeIsSingular(kind, roughness))
    m = microfacetSampleNormal(lobeIsBeckmann(kind), wo, lobeAlpha(roughness), u);
  if (lobeIsRefraction(kind)) return refractDirection(wo, m, eta);
  if (lobeIsGlass(kind) && uChoice >= fresnelDielectric(wo.z, eta))
    return refractDirection(wo, m, eta);
  return reflect(-wo, m);
}

#ifdef MG_PRINCIPLED_LAYERS
// Cycles' interpolate_fresnel_color (bsdf_util.h): F0 blended to white by the dielectric
// Fresnel of relative IOR eta at `cosine`, normalised to run from 0 at normal incidence to 1.
vec3 fresnelInterpolated(vec3 f0, float cosine, float eta) {
  float normal = fresnelDielectric(1.0, eta);
  float fh = (fresnelDielectric(cosine, eta) - normal) / max(1.0 - normal, 1e-6);
  return f0 * (1.0 - fh) + vec3(fh);
}

// The Principled transmission (Cycles 3.4's svm_node_closure_principled, its single-scatter
// GGX glass): a reflection weighted by the Fresnel F of the shading normal, coloured by
// interpolate_fresnel_color of cspec0, of the material's roughness; a refraction weighted by
// max(1 - F, 1e-4), tinted by the base colour, of the lobe's roughness. f |wi.z| per unit
// weight; 0 where the lobe is singular (lobeIsSingular: its refraction's roughness, never
// below its reflection's).
vec3 principledGlassCos(BsdfLobes lobes, int i, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || lobeIsSingular(MG_LOBE_PRINCIPLED_GLASS, lobes.roughness[i]))
    return vec3(0.0);
  float eta = lobes.eta[i];
  float fresnel = fresnelDielectric(wo.z, eta);
  if (wi.z > 0.0) {
    vec3 h = normalize(wo + wi);
    return fresnel * fresnelInterpolated(lobes.glassReflectionF0, dot(wi, h), eta) *
           microfacetReflectionCos(false, lobeAlpha(lobes.glassReflectionRoughness), wo, wi);
  }
  return lobes.glassRefractionColor * max(1.0 - fresnel, 1e-4) *
         microfacetRefractionCos(false, lobeAlpha(lobes.roughness[i]), eta, wo, wi);
}

// Its density: reflection with probability F, refraction with 1 - F (as the Glass lobe).
float principledGlassPdf(BsdfLobes lobes, int i, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || lobeIsSingular(MG_LOBE_PRINCIPLED_GLASS, lobes.roughness[i])) return 0.0;
  float eta = lobes.eta[i];
  float fresnel = fresnelDielectric(wo.z, eta);
  if (wi.z > 0.0)
    return fresnel *
           microfacetReflectionPdf(false, lobeAlpha(lobes.glassReflectionRoughness), wo, wi);
  return (1.0 - fresnel) *
         microfacetRefractionPdf(false, lobeAlpha(lobes.roughness[i]), eta, wo, wi);
}

// A direction from it: reflected below F (uChoice), else refracted, about a GGX visible
// normal of the part's roughness, or about the shading normal where the lobe is singular;
// then `singularWeight` is the part's weight over its probability (per unit weight): the
// reflection's Fresnel colour, the refraction's tint. `eta` and `refractionRoughness` are the
// lobe's (BsdfLobe). The zero vector: total internal reflection of a microfacet.
vec3 principledGlassSample(BsdfLobes lobes, float eta, float refractionRoughness, vec3 wo,
                           vec2 u, float uChoice, out vec3 singularWeight) {
  float fresnel = fresnelDielectric(wo.z, eta);
  bool singular = lobeIsSingular(MG_LOBE_PRINCIPLED_GLASS, refractionRoughness);
  bool reflects = uChoice < fresnel;
  if (singular) {
    singularWeight = reflects ? fresnelInterpolated(lobes.glassReflectionF0, wo.z, eta)
                              : lobes.glassRefractionColor * (max(1.0 - fresnel, 1e-4) /
                                                              max(1.0 - fresnel, 1e-8));
    return reflects ? reflect(-wo, vec3(0.0, 0.0, 1.0))
                    : refractDirection(wo, vec3(0.0, 0.0, 1.0), eta);
  }
  singularWeight = vec3(0.0);
  float roughness = reflects ? lobes.glassReflectionRoughness : refractionRoughness;
  vec3 m = ggxSampleVisibleNormal(wo, lobeAlpha(roughness), u);
  return reflects ? reflect(-wo, m) : refractDirection(wo, m, eta);
}
#endif  // MG_PRINCIPLED_LAYERS

// The material's f(wo, wi) |wi.z|: every lobe's, weighted (the Principled lobe's BRDF is
// coloured by the material's outputs).
vec3 bsdfLobesEvaluateCos(BsdfLobes lobes, vec3 woMaterial, vec3 wiMaterial) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < MG_MAX_LOBES; ++i) {
    if (lobes.pick[i] <= 0.0) continue;  // no weight: nothing to add (a PrincipledLayers slot)
    vec3 wo, wi;
    if (!lobeDirections(lobes, i, woMaterial, wiMaterial, wo, wi)) continue;
#ifdef MG_PRINCIPLED_LAYERS
    if (lobes.kind[i] == MG_LOBE_PRINCIPLED)
      sum += lobes.weight[i] * brdfEvaluateCos(lobes.principled, wo, wi);
    else if (lobes.kind[i] == MG_LOBE_PRINCIPLED_GLASS)
      sum += lobes.weight[i] * principledGlassCos(lobes, i, wo, wi);
    else
#endif
      sum += lobes.weight[i] *
             lobeEvaluateCos(lobes.kind[i], lobes.roughness[i], lobes.eta[i], wo, wi);
  }
  return sum;
}

// The density of bsdfLobesSample: the lobes' densities mixed by their pick probabilities.
float bsdfLobesPdf(BsdfLobes lobes, vec3 woMaterial, vec3 wiMaterial) {
  float pdf = 0.0;
  for (int i = 0; i < MG_MAX_LOBES; ++i) {
    if (lobes.pick[i] <= 0.0) continue;
    // A direction a lobe's sample may not take (lobeDirections) has no density from it.
    vec3 wo, wi;
    if (!lobeDirections(lobes, i, woMaterial, wiMaterial, wo, wi)) continue;
#ifdef MG_PRINCIPLED_LAYERS
    pdf += lobes.pick[i] *
           (lobes.kind[i] == MG_LOBE_PRINCIPLED ? brdfPdf(lobes.principled, wo, wi)
            : lobes.kind[i] == MG_LOBE_PRINCIPLED_GLASS
                ? principledGlassPdf(lobes, i, wo, wi)
                : lobePdf(lobes.kind[i], lobes.roughness[i], lobes.eta[i], wo, wi));
#else
    pdf += lobes.pick[i] * lobePdf(lobes.kind[i], lobes.roughness[i], lobes.eta[i], wo, wi);
#endif
  }
  return pdf;
}

// The lobe that uLobe in [0, 1) picks by the pick probabilities (-1: none has weight), and
// uLobe's place within the lobe's share, again uniform in [0, 1) (`uWithin`).
int bsdfLobesPick(BsdfLobes lobes, float uLobe, out float uWithin) {
  int picked = -1;
  float cumulative = 0.0;
  uWithin = 0.0;
  for (int i = 0; i < MG_MAX_LOBES; ++i) {
    if (lobes.pick[i] <= 0.0) continue;
    picked = i;  // the last one with weight also takes uLobe's float round-off above the sum
    uWithin = clamp((uLobe - cumulative) / lobes.pick[i], 0.0, 0.99999994);
    cumulative += lobes.pick[i];
    if (uLobe < cumulative) break;
  }
  return picked;
}

// Whether some lobe sends light through the surface: light sampling then looks on both sides.
bool bsdfLobesTransmit(BsdfLobes lobes) {
  for (int i = 0; i < MG_MAX_LOBES; ++i)
    if (lobes.pick[i] > 0.0 && lobeTransmits(lobes.kind[i])) return true;
  return false;
}

// One lobe's fields, copied out of BsdfLobes.
struct BsdfLobe {
  vec3 weight;
  int kind;
  float roughness;
  float eta;
  float pick;
#ifdef MG_LOBE_NORMALS
  bool ownNormal;
  mat3 toLobe;
#endif
};

// Lobe `index`'s fields, each slot read with a constant index once the loop is unrolled
// (see BsdfLobes). Slot 0 is copied first, so that every field is set whatever `index` is.
BsdfLobe bsdfLobeAt(BsdfLobes lobes, int index) {
  BsdfLobe lobe;
  for (int i = 0; i < MG_MAX_LOBES; ++i) {
    if (i != 0 && i != index) continue;
    lobe.weight = lobes.weight[i];
    lobe.kind = lobes.kind[i];
    lobe.roughness = lobes.roughness[i];
    lobe.eta = lobes.eta[i];
    lobe.pick = lobes.pick[i];
#ifdef MG_LOBE_NORMALS
    lobe.ownNormal = lobes.ownNormal[i];
    lobe.toLobe = lobes.toLobe[i];
#endif
  }
  return lobe;
}

// One direction drawn from the lobes (the one-sample mixture model): `weight` is the
// throughput factor f |wi.z| / pdf. A singular lobe's sample is that lobe's alone (weight
// its weight x singularWeight over its pick probability; `pdf` 0, as the other lobes and
// light sampling cannot draw it); any other's is weighted by the whole BSDF over the
// mixture's density (`pdf`). `sampled`: the lobe drawn from. `diffuse`: the direction came
// from a diffuse closure (Diffuse, Velvet, Translucent, the sheen, the Principled lobe's
// diffuse part), as Cycles labels a bounce. False: no direction.
bool bsdfLobesSample(BsdfLobes lobes, vec3 woMaterial, float uLobe, vec2 u, out vec3 wi,
                     out vec3 weight, out float pdf, out BsdfLobe sampled, out bool diffuse) {
  float uChoice;
  int picked = bsdfLobesPick(lobes, uLobe, uChoice);
  sampled = bsdfLobeAt(lobes, max(picked, 0));
  weight = vec3(0.0);
  pdf = 0.0;
  wi = vec3(0.0, 0.0, 1.0);
  diffuse = false;
  if (picked < 0) return false;
  vec3 wo = woMaterial;  // in the sampled lobe's frame
#ifdef MG_LOBE_NORMALS
  if (sampled.ownNormal) {
    wo = sampled.toLobe * woMaterial;
    if (!(wo.z > 0.0)) return false;  // the viewer is below the lobe: it scatters nothing
  }
#endif
  int kind = sampled.kind;
  float roughness = sampled.roughness;
  float singularWeight = 1.0;
  vec3 singularColor = vec3(1.0);
  diffuse = kind == MG_LOBE_DIFFUSE || kind == MG_LOBE_VELVET || kind == MG_LOBE_TRANSLUCENT ||
            kind == MG_LOBE_PRINCIPLED_SHEEN;
#ifdef MG_PRINCIPLED_LAYERS
  if (kind == MG_LOBE_PRINCIPLED) {
    // brdfSample picks its specular part below the specular probability, its diffuse above.
    wi = brdfSample(lobes.principled, wo, uChoice, u);
    diffuse = uChoice >= brdfSpecularProbability(lobes.principled, wo);
  } else if (kind == MG_LOBE_PRINCIPLED_GLASS) {
    wi = principledGlassSample(lobes, sampled.eta, roughness, wo, u, uChoice, singularColor);
  } else
#endif
  {
    wi = lobeSample(kind, roughness, sampled.eta, wo, u, uChoice, singularWeight);
  }
  if (!(dot(wi, wi) > 0.0)) return false;
  wi = normalize(wi);
#ifdef MG_LOBE_NORMALS
  if (sampled.ownNormal) wi = wi * sampled.toLobe;  // back to the material's frame (transpose)
  vec3 woUnused, wiLobe;
  if (!lobeFrameDirections(lobes, sampled.ownNormal, sampled.toLobe, woMaterial, wi, woUnused,
                           wiLobe))
    return false;
#endif
  if (lobeIsSingular(kind, roughness)) {
    weight = sampled.weight * singularColor * (singularWeight / sampled.pick);
    return true;
  }
  pdf = bsdfLobesPdf(lobes, woMaterial, wi);
  if (!(pdf > 0.0)) return false;
  weight = bsdfLobesEvaluateCos(lobes, woMaterial, wi) / pdf;
  return true;
}

#endif  // MG_BSDF_LOBES
