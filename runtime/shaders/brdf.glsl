// The BRDF of thesis §2.1: Lambert (eq. 2.2) plus GGX microfacet specular (eq. 2.3) with
// Schlick's Fresnel (2.4), separable Smith shadowing-masking (2.5, 2.6) and the GGX
// distribution (2.7); directions sampled from the GGX visible normals (Heitz 2018).

const float kPi = 3.14159265358979;
// Reflectance at normal incidence of dielectrics in the metallic workflow, per unit of the
// material's specular output: F0 = 0.08 * specular, Blender's Principled BSDF convention
// (specular 0.5, its default, gives the usual 0.04).
const float kDielectricF0PerSpecular = 0.08;

struct BrdfParameters {
  vec3 diffuse;  // k_d of eq. 2.2, already weighted by the dielectric share
  vec3 f0;       // F_0 of eq. 2.4
  float alpha;   // GGX alpha = perceptual roughness^2
};

BrdfParameters brdfFromMaterial(vec3 baseColor, float metallic, float roughness,
                                float specular) {
  BrdfParameters brdf;
  metallic = clamp(metallic, 0.0, 1.0);
  float dielectricF0 = clamp(kDielectricF0PerSpecular * specular, 0.0, 1.0);
  // The diffuse share is what the dielectric specular layer does not reflect at normal
  // incidence, so an albedo-1 dielectric reflects about 1 in total (white furnace).
  brdf.diffuse = baseColor * (1.0 - metallic) * (1.0 - dielectricF0);
  brdf.f0 = mix(vec3(dielectricF0), baseColor, metallic);
  float r = clamp(roughness, 0.02, 1.0);
  brdf.alpha = r * r;
  return brdf;
}

// Eq. 2.4.
vec3 fresnelSchlick(vec3 f0, float cosTheta) {
  float m = clamp(1.0 - cosTheta, 0.0, 1.0);
  float m2 = m * m;
  return f0 + (1.0 - f0) * (m2 * m2 * m);
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
  vec3 f = fresnelSchlick(brdf.f0, dot(wi, h));
  float g = smithG1(wi.z, brdf.alpha) * smithG1(wo.z, brdf.alpha);  // eq. 2.5
  vec3 specular = f * g * ggxD(h.z, brdf.alpha) / (4.0 * wi.z * wo.z);
  return (brdf.diffuse / kPi + specular) * wi.z;
}

// Probability of sampling the specular lobe: its share of the reflectance at wo.
float brdfSpecularProbability(BrdfParameters brdf, vec3 wo) {
  vec3 weights = vec3(0.2126, 0.7152, 0.0722);
  float specular = dot(fresnelSchlick(brdf.f0, wo.z), weights);
  float diffuse = dot(brdf.diffuse, weights);
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
