// The BRDF of thesis §2.1: Lambert (eq. 2.2) plus GGX microfacet specular (eq. 2.3) with
// Schlick's Fresnel (2.4), separable Smith shadowing-masking (2.5, 2.6) and the GGX
// distribution (2.7); directions sampled from the GGX visible normals (Heitz 2018).
//
// A material may ask for Cycles 3.4's Principled BSDF v1 instead (its cyclesPrincipled
// output; the Blender exporter sets it to 1 for a Principled BSDF): the weights and shapes
// of Cycles' svm_node_closure_bsdf, case CLOSURE_BSDF_PRINCIPLED_ID (kernel/svm/closure.h):
// - the diffuse closure is weighted by base colour * (1 - metallic) alone: Cycles does not
//   take the specular layer's reflectance away from it, so a white dielectric reflects a
//   little more than all light (not energy-conserving; memograph's own weighting below is);
// - the diffuse is Burley's with the roughness-dependent retro-reflection
//   (bsdf_principled_diffuse_compute_brdf, kernel/closure/bsdf_principled_diffuse.h);
// - the specular's Fresnel blends F0 (cspec0) to white by the dielectric Fresnel of the IOR
//   that Specular gives, normalised to 0 at normal incidence (interpolate_fresnel_color,
//   kernel/closure/bsdf_util.h, used by reflection_color in bsdf_microfacet.h) instead of
//   Schlick's (1 - cos)^5.
// Values between 0 and 1 blend the two BRDFs linearly (a Mix Shader of two Principled).
// The specular tint applies in both: F0 as Cycles computes cspec0.

const float kPi = 3.14159265358979;
// Reflectance at normal incidence of dielectrics in the metallic workflow, per unit of the
// material's specular output: F0 = 0.08 * specular, Blender's Principled BSDF convention
// (specular 0.5, its default, gives the usual 0.04).
const float kDielectricF0PerSpecular = 0.08;

struct BrdfParameters {
  vec3 diffuse;        // k_d of eq. 2.2 (Lambert), already weighted by the dielectric share
  vec3 diffuseBurley;  // Cycles' Principled diffuse weight (cyclesPrincipled share), Burley
  vec3 f0;             // F_0 of eq. 2.4 (Cycles' cspec0)
  float alpha;         // GGX alpha = perceptual roughness^2
  float roughness;     // perceptual roughness, for Burley's retro-reflection
  float cycles;        // the cyclesPrincipled share of the Fresnel: 0 Schlick, 1 Cycles'
  float dielectricF0;  // 0.08 * specular: the IOR of Cycles' Fresnel
};

// Specular tint as Cycles 3.4 computes it (svm/closure.h, "specular reflection" of the
// Principled case): the base colour normalised by its luminance approximation
// 0.3 R + 0.6 G + 0.1 B (white when that is 0), mixed from white by specularTint.
vec3 specularTintColor(vec3 baseColor, float specularTint) {
  float luminance = dot(baseColor, vec3(0.3, 0.6, 0.1));
  vec3 tint = luminance > 0.0 ? baseColor / luminance : vec3(1.0);
  return mix(vec3(1.0), tint, clamp(specularTint, 0.0, 1.0));
}

BrdfParameters brdfFromMaterial(vec3 baseColor, float metallic, float roughness, float specular,
                                float specularTint, float cyclesPrincipled) {
  BrdfParameters brdf;
  metallic = clamp(metallic, 0.0, 1.0);
  float dielectricF0 = clamp(kDielectricF0PerSpecular * specular, 0.0, 1.0);
#ifdef MG_CYCLES_PRINCIPLED
  float cycles = clamp(cyclesPrincipled, 0.0, 1.0);
  // Cycles' cspec0 = 0.08 specular tint (1 - metallic) + baseColor metallic, clamped to
  // [0, 1] (bsdf_microfacet_ggx_fresnel_setup saturates it).
  vec3 dielectricF0Tinted = clamp(
      kDielectricF0PerSpecular * specular * specularTintColor(baseColor, specularTint), 0.0, 1.0);
#else
  // No material of the scene writes specularTint or cyclesPrincipled (the renderer defines
  // MG_CYCLES_PRINCIPLED when one does): both are 0, and their code folds away, so such a
  // scene's path tracer carries none of it (its registers are the kernel's scarcest resource).
  const float cycles = 0.0;
  vec3 dielectricF0Tinted = vec3(dielectricF0);
#endif
  // memograph: the diffuse share is what the dielectric specular layer does not reflect at
  // normal incidence, so an albedo-1 dielectric reflects about 1 in total (white furnace).
  // Cycles: diffuse_weight = (1 - metallic) (1 - transmission), nothing taken for the
  // specular (transmission is not carried).
  vec3 diffuse = baseColor * (1.0 - metallic);
  brdf.diffuse = (1.0 - cycles) * diffuse * (1.0 - dielectricF0Tinted);
  brdf.diffuseBurley = vec3(0.0);
#ifdef MG_CYCLES_PRINCIPLED
  brdf.diffuseBurley = cycles * diffuse;
#endif
  brdf.f0 = mix(dielectricF0Tinted, baseColor, metallic);
  float r = clamp(roughness, 0.02, 1.0);
  brdf.alpha = r * r;
  brdf.roughness = clamp(roughness, 0.0, 1.0);
  brdf.cycles = cycles;
  brdf.dielectricF0 = dielectricF0;
  return brdf;
}

// Eq. 2.4.
vec3 fresnelSchlick(vec3 f0, float cosTheta) {
  float m = clamp(1.0 - cosTheta, 0.0, 1.0);
  float m2 = m * m;
  return f0 + (1.0 - f0) * (m2 * m2 * m);
}

// The unpolarised Fresnel reflectance of a dielectric of relative IOR eta at incidence
// cosine c (no refracted direction needed; 1 under total internal reflection).
float fresnelDielectric(float c, float eta) {
  c = abs(c);
  float g = eta * eta - 1.0 + c * c;
  if (g <= 0.0)
    return 1.0;
  g = sqrt(g);
  float a = (g - c) / (g + c);
  float b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

// Cycles 3.4's Principled specular Fresnel (interpolate_fresnel_color): F0 blended to white
// by the dielectric Fresnel of the IOR 2 / (1 - sqrt(0.08 specular)) - 1 (whose normal
// reflectance is dielectricF0), normalised to run from 0 at normal incidence to 1.
vec3 fresnelCycles(vec3 f0, float dielectricF0, float cosTheta) {
  float F0 = min(dielectricF0, 0.99);
  float eta = 2.0 / (1.0 - sqrt(F0)) - 1.0;
  float fh = (fresnelDielectric(cosTheta, eta) - F0) / (1.0 - F0);
  return f0 + (1.0 - f0) * fh;
}

vec3 brdfFresnel(BrdfParameters brdf, float cosTheta) {
  vec3 f = fresnelSchlick(brdf.f0, cosTheta);
#ifdef MG_CYCLES_PRINCIPLED
  if (brdf.cycles > 0.0)
    f = mix(f, fresnelCycles(brdf.f0, brdf.dielectricF0, cosTheta), brdf.cycles);
#endif
  return f;
}

// Burley's diffuse of Cycles' Principled BSDF (bsdf_principled_diffuse_compute_brdf,
// PRINCIPLED_DIFFUSE_FULL) over 1/pi: the Lambertian part (1 - F_V / 2)(1 - F_L / 2) plus
// the retro-reflection RR (F_L + F_V + F_L F_V (RR - 1)), RR = roughness (1 + wi.wo),
// with F = (1 - cos)^5.
float burleyDiffuse(float roughness, vec3 wo, vec3 wi) {
  float fv = fresnelSchlick(vec3(0.0), wo.z).x;
  float fl = fresnelSchlick(vec3(0.0), wi.z).x;
  float rr = roughness * (dot(wi, wo) + 1.0);
  return (1.0 - 0.5 * fv) * (1.0 - 0.5 * fl) + rr * (fl + fv + fl * fv * (rr - 1.0));
}

// Eq. 2.6 (the Heaviside factor is applied by the caller through the half vector).
float smithG1(float cosTheta, float alpha) {
  float c = abs(cosTheta);
  float a2 = alpha * alpha;
  return 2.0 * c / (c + sqrt(a2 + (1.0 - a2) * c * c));
}

// Eq. 2.7.
float ggxD(float cosThetaH, float alpha) {
  if (cosThetaH <= 0.0) return 0.0;
  float a2 = alpha * alpha;
  float d = cosThetaH * cosThetaH * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
}

// f(wo, wi) * |n.wi| in a local frame where the normal is +z (eq. 2.2 + eq. 2.3).
vec3 brdfEvaluateCos(BrdfParameters brdf, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
  vec3 h = normalize(wo + wi);
  vec3 f = brdfFresnel(brdf, dot(wi, h));
  float g = smithG1(wi.z, brdf.alpha) * smithG1(wo.z, brdf.alpha);  // eq. 2.5
  vec3 specular = f * g * ggxD(h.z, brdf.alpha) / (4.0 * wi.z * wo.z);
  vec3 diffuse = brdf.diffuse;
#ifdef MG_CYCLES_PRINCIPLED
  if (brdf.cycles > 0.0)
    diffuse += brdf.diffuseBurley * burleyDiffuse(brdf.roughness, wo, wi);
#endif
  return (diffuse / kPi + specular) * wi.z;
}

// Probability of sampling the specular lobe: its share of the reflectance at wo.
float brdfSpecularProbability(BrdfParameters brdf, vec3 wo) {
  vec3 weights = vec3(0.2126, 0.7152, 0.0722);
  float specular = dot(brdfFresnel(brdf, wo.z), weights);
#ifdef MG_CYCLES_PRINCIPLED
  float diffuse = dot(brdf.diffuse + brdf.diffuseBurley, weights);
#else
  float diffuse = dot(brdf.diffuse, weights);
#endif
  return clamp(specular / max(specular + diffuse, 1e-6), 0.1, 0.9);
}

// Heitz 2018, "Sampling the GGX Distribution of Visible Normals": a half vector seen from wo.
vec3 ggxSampleVisibleNormal(vec3 wo, float alpha, vec2 u) {
  vec3 vh = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float lensq = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x);
  float phi = 2.0 * kPi * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5 * (1.0 + vh.z);
  p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0, nh.z)));
}

// Density of brdfSample's mixture (cosine-weighted diffuse + GGX visible normals) for wi.
float brdfPdf(BrdfParameters brdf, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  float pSpecular = brdfSpecularProbability(brdf, wo);
  vec3 h = normalize(wo + wi);
  // pdf(wi) = G1(wo) D(h) / (4 wo.z) for reflection of visible normals.
  float specularPdf = smithG1(wo.z, brdf.alpha) * ggxD(h.z, brdf.alpha) / (4.0 * wo.z);
  float diffusePdf = wi.z / kPi;
  return mix(diffusePdf, specularPdf, pSpecular);
}

// Samples an incident direction wi (local frame) from the lobe mixture.
vec3 brdfSample(BrdfParameters brdf, vec3 wo, float uLobe, vec2 u) {
  if (uLobe < brdfSpecularProbability(brdf, wo)) {
    vec3 h = ggxSampleVisibleNormal(wo, brdf.alpha, u);
    return reflect(-wo, h);
  }
  float r = sqrt(u.x);
  float phi = 2.0 * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
}
