// Path shading written once for both architectures: the megakernel (path_tracer.glsl, one
// thread runs a whole path) and the wavefront passes (wavefront.glsl, one pass per stage of
// a bounce; Laine, Karras and Aila, "Megakernels Considered Harmful", HPG 2013). Nothing here
// traces a ray: each architecture traces where its structure wants the ray (in place, or
// from a queue). Needs scene_bindings.glsl, brdf.glsl, ray_cone.glsl, rng.glsl and the trace
// backend's HitInfo (trace_hit.glsl) first.
// Moves a ray origin off a surface along its geometric normal, scaled to the float
// precision at that position (Wächter and Binder, Ray Tracing Gems, ch. 6).
vec3 offsetRayOrigin(vec3 p, vec3 n) {
  const float kOrigin = 1.0 / 32.0;
  const float kFloatScale = 1.0 / 65536.0;
  const float kIntScale = 256.0;
  ivec3 offset = ivec3(kIntScale * n);
  vec3 pInt = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0 ? -offset.x : offset.x)),
                   intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0 ? -offset.y : offset.y)),
                   intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0 ? -offset.z : offset.z)));
  return vec3(abs(p.x) < kOrigin ? p.x + kFloatScale * n.x : pInt.x,
              abs(p.y) < kOrigin ? p.y + kFloatScale * n.y : pInt.y,
              abs(p.z) < kOrigin ? p.z + kFloatScale * n.z : pInt.z);
}

// An orthonormal basis around n (Duff et al. 2017).
void basisAround(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Radiance arriving from the environment along direction d.
vec3 environmentRadiance(vec3 d) {
  vec3 scale = frame.environment.rgb;
  if ((frame.path.z & kFlagEnvironmentImage) == 0u) return scale;
  // Equirectangular: u around +y starting at -z, v from the zenith down.
  uvec2 size = frame.environmentSize.xy;
  float u = atan(d.x, -d.z) * (0.5 / kPi) + 0.5;
  float v = acos(clamp(d.y, -1.0, 1.0)) / kPi;
  uint x = min(uint(u * float(size.x)), size.x - 1u);
  uint y = min(uint(v * float(size.y)), size.y - 1u);
  return environmentTexels[y * size.x + x].rgb * scale;
}

// A hit turned into what shading needs: material inputs (with ray-cone derivatives) and
// the geometric normal, facing the incoming ray.
struct SurfaceHit {
  MaterialInputs inputs;
  uint materialId;
  // The hit's instance and its mesh: what an object-space cache key names (texel_cache.glsl
  // evaluateMaterialThroughCut), as the object-space position alone is the same on every
  // instance of a mesh.
  uvec2 object;
  vec3 geometricNormal;
  float curvature;
  float coneWidth;
  float lightAreaPdf;  // emissive NEE's area pdf of this point (0: not a sampled light)
  bool entering;       // the ray hit the front face: a transmission lobe's IOR is entered
};

SurfaceHit surfaceAt(HitInfo hit, vec3 origin, vec3 direction, RayCone cone) {
  SurfaceHit s;
  Instance instance = instances[hit.instanceIndex];
  // The triangles the TLAS holds: the mesh's, or its LOD's (ids.z); object keys keep ids.x.
  Mesh mesh = meshes[instance.ids.z];
  s.materialId = instance.ids.y;
  s.object = uvec2(hit.instanceIndex, instance.ids.x);
  s.lightAreaPdf = instance.objectInfo.y;
  uint firstVertex = mesh.ranges.x;
  uint firstIndex = mesh.ranges.y + 3u * hit.primitiveIndex;
  Vertex v0 = vertices[firstVertex + indices[firstIndex]];
  Vertex v1 = vertices[firstVertex + indices[firstIndex + 1u]];
  Vertex v2 = vertices[firstVertex + indices[firstIndex + 2u]];
  vec3 w = vec3(1.0 - hit.barycentrics.x - hit.barycentrics.y, hit.barycentrics);

  mat4 toWorld = instance.objectToWorld;
  mat3 normalToWorld = mat3(instance.normalToWorld);
  vec3 p0 = (toWorld * vec4(v0.position.xyz, 1.0)).xyz;
  vec3 p1 = (toWorld * vec4(v1.position.xyz, 1.0)).xyz;
  vec3 p2 = (toWorld * vec4(v2.position.xyz, 1.0)).xyz;
  vec3 n0 = normalize(normalToWorld * v0.normal.xyz);
  vec3 n1 = normalize(normalToWorld * v1.normal.xyz);
  vec3 n2 = normalize(normalToWorld * v2.normal.xyz);
  vec3 position = origin + hit.t * direction;

  // Imported meshes hold degenerate triangles and zero normals: fall back rather than let a
  // NaN into the accumulation.
  vec3 n = w.x * n0 + w.y * n1 + w.z * n2;
  vec3 ng = cross(p1 - p0, p2 - p0);
  if (!(dot(ng, ng) > 1e-30)) ng = dot(n, n) > 1e-30 ? n : -direction;
  ng = normalize(ng);
  n = dot(n, n) > 1e-30 ? normalize(n) : ng;
  // The front face winds counter-clockwise in object space; a mirroring transform reverses
  // the winding of the world-space vertices, so the face normal flips with it (Blender's
  // Geometry Backfacing).
  vec3 front = determinant(mat3(toWorld)) < 0.0 ? -ng : ng;
  bool backfacing = dot(front, direction) > 0.0;
  s.entering = !backfacing;
  // Two-sided surfaces: both normals face the ray.
  if (dot(ng, direction) > 0.0) ng = -ng;
  bool flipped = dot(n, ng) < 0.0;
  if (flipped) n = -n;
  s.geometricNormal = ng;
  // The curvature of the normals the hit shades with: flipped on a back face (eq. 2.12 then
  // sees a convex surface as convex from either side).
  s.curvature = (flipped ? -1.0 : 1.0) * triangleCurvature(p0, p1, p2, n0, n1, n2);

  // Eq. 2.10, then the footprint ellipse (eq. 2.13-2.16) mapped to UVs through the
  // barycentrics of its vertex and co-vertex.
  s.coneWidth = rayConeWidthAt(cone, hit.t);
  vec3 axis1, axis2;
  rayConeEllipseAxes(direction, ng, s.coneWidth, axis1, axis2);
  vec2 b1 = barycentricsOf(position + axis1, p0, p1, p2);
  vec2 b2 = barycentricsOf(position + axis2, p0, p1, p2);
  vec2 uv0 = vec2(v0.position.w, v0.normal.w);
  vec2 uv1 = vec2(v1.position.w, v1.normal.w);
  vec2 uv2 = vec2(v2.position.w, v2.normal.w);
  vec2 uv = w.x * uv0 + w.y * uv1 + w.z * uv2;
  vec2 uvAt1 = uv0 + b1.x * (uv1 - uv0) + b1.y * (uv2 - uv0);
  vec2 uvAt2 = uv0 + b2.x * (uv1 - uv0) + b2.y * (uv2 - uv0);

  s.inputs.uv.v = uv;
  s.inputs.uv.x = uvAt1 - uv;
  s.inputs.uv.y = uvAt2 - uv;
  s.inputs.position.v = position;
  s.inputs.position.x = axis1;
  s.inputs.position.y = axis2;
  s.inputs.normal = n;
#ifndef MG_OMIT_TRACED_INPUTS
  s.inputs.ambientOcclusion = 1.0;  // nothing traced yet: the megakernel's setTracedInputs
  s.inputs.bevelNormal = n;
#endif

  vec3 tangent;
  float handedness = 1.0;
  if ((mesh.ranges.z & kMeshHasTangents) != 0u) {
    tangent = mat3(toWorld) * (w.x * v0.tangent.xyz + w.y * v1.tangent.xyz +
                               w.z * v2.tangent.xyz);
    handedness = v0.tangent.w < 0.0 ? -1.0 : 1.0;
  } else {
    // Tangent along +u from the triangle's UV parametrization.
    vec2 duv1 = uv1 - uv0;
    vec2 duv2 = uv2 - uv0;
    float det = duv1.x * duv2.y - duv1.y * duv2.x;
    tangent = abs(det) > 1e-12 ? ((p1 - p0) * duv2.y - (p2 - p0) * duv1.y) / det : vec3(0.0);
  }
  tangent = projectOnPlane(tangent, n);
  if (dot(tangent, tangent) < 1e-12) {
    vec3 unused;
    basisAround(n, tangent, unused);
  }
  s.inputs.tangent = normalize(tangent);
  s.inputs.bitangentSign = vec3(handedness, 0.0, 0.0);
  s.inputs.vertexColor = (mesh.ranges.z & kMeshHasColors) != 0u
                             ? w.x * v0.color + w.y * v1.color + w.z * v2.color
                             : vec4(1.0);
  s.inputs.view = -direction;
  s.inputs.time = frame.cameraForward.w;
  s.inputs.textureBase = 0;  // set per material by the switch case or the callable

  // Object space (Blender's Object and Generated coordinates, Object Info): the hit and its
  // footprint axes through the inverse transform, then the mesh's texture space. Compiled
  // out for scenes whose materials read none of it (MG_OMIT_OBJECT_INPUTS, render_pipelines.cpp).
#ifndef MG_OMIT_OBJECT_INPUTS
  mat4 toObject = instance.worldToObject;
  s.inputs.objectPosition.v = (toObject * vec4(position, 1.0)).xyz;
  s.inputs.objectPosition.x = mat3(toObject) * axis1;
  s.inputs.objectPosition.y = mat3(toObject) * axis2;
  vec3 toGenerated = 0.5 / mesh.textureSpaceSize.xyz;
  s.inputs.generated.v =
      (s.inputs.objectPosition.v - mesh.textureSpaceLocation.xyz) * toGenerated + 0.5;
  s.inputs.generated.x = s.inputs.objectPosition.x * toGenerated;
  s.inputs.generated.y = s.inputs.objectPosition.y * toGenerated;
  s.inputs.generatedScale = toGenerated;
  s.inputs.geometricNormal = ng;
  // A normal maps to world space by the inverse transpose of the object's linear part, so
  // back by its transpose (Cycles 3.4 object_inverse_normal_transform, then safe_normalize).
  vec3 objectNormal = transpose(mat3(toWorld)) * s.inputs.normal;
  s.inputs.objectNormal = dot(objectNormal, objectNormal) > 1e-30 ? normalize(objectNormal)
                                                                  : vec3(0.0);
  s.inputs.objectLocation = toWorld[3].xyz;
  s.inputs.objectRandom = instance.objectInfo.x;
  s.inputs.backfacing = backfacing ? 1.0 : 0.0;
#endif
  return s;
}

// The path state that Blender's Light Path node reads (MaterialInputs rayFlags and the
// depths), kept as Cycles 3.4 keeps it (kernel/integrator/path_state.h path_state_init_integrator
// and path_state_next): how the ray left the last vertex and the bounces so far, overall and
// by lobe. A shadow ray evaluates a material only where it may pass through it
// (transparent_shadow.glsl, MG_TRANSPARENT_SHADOWS): only then is MG_RAY_SHADOW set. A
// Transparent lobe's ray keeps the state it came with (Cycles counts it as a
// transparent bounce, which Light Path's depths leave out). The ray's kind is the tracer's own
// (kPathRay*), turned into the prelude's MG_RAY_* bits only where MaterialInputs has the path
// state, so that the tracer compiles with a node library whose prelude has none of it. Scenes
// whose graphs read none of it (MG_OMIT_PATH_INPUTS) carry it along unread, and the compilers
// drop it.
const int kPathRayCamera = 0;       // the camera ray
const int kPathRayDiffuse = 1;      // reflected by the diffuse lobe
const int kPathRayGlossy = 2;       // reflected by the GGX lobe
const int kPathRaySingular = 3;     // reflected by a GGX lobe Cycles takes as a perfect mirror
const int kPathRayLightSample = 4;  // a light sample's ray to an emitter
const int kPathRayTransmitGlossy = 5;    // refracted by a rough Refraction or Glass lobe
const int kPathRayTransmitSingular = 6;  // refracted by a smooth one
const int kPathRayTransmitDiffuse = 7;   // sent through by the Translucent lobe
#ifdef MG_TRANSPARENT_SHADOWS
// Only with transparent shadows, so that the other scenes' passes hold no constant more.
const int kPathRayShadow = 8;  // a shadow ray at a surface it may pass through
#endif

struct PathState {
  int ray;  // kPathRay*
  int depth;
  int diffuseDepth;
  int glossyDepth;
  int transmissionDepth;
#ifdef MG_FILTER_GLOSSY_INVERSE
  // Cycles 3.4's min_ray_pdf (path_state.h): the smallest BSDF pdf of the path's bounces so
  // far, what Filter Glossy blurs by (filterGlossy). Only in scenes rendered with it.
  float minRayPdf;
#endif
};
#ifdef MG_FILTER_GLOSSY_INVERSE
const float kFloatMax = 3.402823466e38;  // C's FLT_MAX
#endif

// A camera ray's state: the path's start (Cycles' PATH_RAY_CAMERA, every depth 0).
PathState cameraPathState() {
  PathState path;
  path.ray = kPathRayCamera;
  path.depth = 0;
  path.diffuseDepth = 0;
  path.glossyDepth = 0;
  path.transmissionDepth = 0;
#ifdef MG_FILTER_GLOSSY_INVERSE
  path.minRayPdf = kFloatMax;  // Cycles' path_state_init_integrator: FLT_MAX at the camera
#endif
  return path;
}

#ifdef MG_FILTER_GLOSSY_INVERSE
// The path's smallest bounce pdf after a BSDF-sampled bounce of density `bsdfPdf` (Cycles 3.4
// shade_surface.h integrate_surface_bsdf_bssrdf_bounce: min_ray_pdf = min(min_ray_pdf, pdf),
// the pdf of the closures' mixture, skipped for a transparent bounce). A singular lobe's
// bounce (pdf 0 here) leaves it: Cycles gives a perfect mirror or refraction the stand-in pdf
// 1e6 (bsdf_reflection.h, bsdf_refraction.h, bsdf_microfacet.h's alpha^2 <= 1e-7 case), which
// lowers it only to about 1e6 x the lobe's pick share s, and blurs nothing unless Filter Glossy
// exceeds 1e6 s. The Transparent lobe is singular too, so it is skipped as Cycles skips it.
void pathStateAfterBsdfPdf(inout PathState path, float bsdfPdf) {
  if (bsdfPdf > 0.0) path.minRayPdf = min(path.minRayPdf, bsdfPdf);
}
#endif

// A reflection by the lobe continuePath sampled: diffuse, or the GGX lobe (glossy, and
// singular where Cycles' microfacet is a perfect mirror: alpha_x alpha_y <= 1e-7 in
// bsdf_microfacet.h, alpha = roughness^2; a Glossy lobe there is a mirror, the Principled
// BRDF's GGX clamps its roughness at 0.02 but labels the bounce as Cycles would). Cycles counts a singular bounce as a glossy one.
void pathStateAfterReflection(inout PathState path, bool specularLobe, float roughness) {
  path.depth += 1;
  if (specularLobe) {
    path.glossyDepth += 1;
    float alpha = roughness * roughness;
    path.ray = alpha * alpha <= 1e-7 ? kPathRaySingular : kPathRayGlossy;
  } else {
    path.diffuseDepth += 1;
    path.ray = kPathRayDiffuse;
  }
}

// A transmission through the surface by a lobe of bsdf_lobes.glsl: Cycles' path_state_next
// counts it as a transmission bounce (not a diffuse or glossy one) and labels the ray
// transmit, and diffuse (Translucent), glossy, or glossy and singular (smooth refraction).
void pathStateAfterTransmission(inout PathState path, bool diffuse, bool singular) {
  path.depth += 1;
  path.transmissionDepth += 1;
  path.ray = diffuse ? kPathRayTransmitDiffuse
                     : (singular ? kPathRayTransmitSingular : kPathRayTransmitGlossy);
}

// The state an emitter's graph sees when it is evaluated for a light sample of the vertex
// whose state is `path` (Cycles' light_sample_shader_eval: PATH_RAY_EMISSION alone, so no
// flag; svm_node_light_path then counts Ray Depth one bounce further, the lobes' depths not).
PathState lightSamplePathState(PathState path) {
  path.ray = kPathRayLightSample;
  path.depth += 1;
  return path;
}

#ifdef MG_TRANSPARENT_SHADOWS
// The state a maybe-transparent surface's graph sees at a shadow ray's hit, from the light
// sample's (lightSamplePathState): Cycles evaluates it with PATH_RAY_SHADOW alone
// (shade_shadow.h), and Light Path counts its Ray Depth one bounce further, as for emission.
PathState shadowPathState(PathState lightSample) {
  lightSample.ray = kPathRayShadow;
  return lightSample;
}
#endif

// Puts the path state and the ray's length to the hit (the ray's t: its direction is unit)
// into a hit's material inputs.
void setPathInputs(inout MaterialInputs inputs, PathState path, float rayLength) {
#ifndef MG_OMIT_PATH_INPUTS
  int flags = 0;  // kPathRayLightSample: Cycles' PATH_RAY_EMISSION, which Light Path ignores
  if (path.ray == kPathRayCamera) flags = MG_RAY_CAMERA;
  else if (path.ray == kPathRayDiffuse) flags = MG_RAY_REFLECT | MG_RAY_DIFFUSE;
  else if (path.ray == kPathRayGlossy) flags = MG_RAY_REFLECT | MG_RAY_GLOSSY;
  else if (path.ray == kPathRaySingular) flags = MG_RAY_REFLECT | MG_RAY_GLOSSY | MG_RAY_SINGULAR;
  else if (path.ray == kPathRayTransmitGlossy) flags = MG_RAY_TRANSMIT | MG_RAY_GLOSSY;
  else if (path.ray == kPathRayTransmitSingular)
    flags = MG_RAY_TRANSMIT | MG_RAY_GLOSSY | MG_RAY_SINGULAR;
  else if (path.ray == kPathRayTransmitDiffuse) flags = MG_RAY_TRANSMIT | MG_RAY_DIFFUSE;
#ifdef MG_TRANSPARENT_SHADOWS
  else if (path.ray == kPathRayShadow) flags = MG_RAY_SHADOW;
#endif
  inputs.rayFlags = flags;
  inputs.rayLength = rayLength;
  inputs.rayDepth = path.depth;
  inputs.diffuseDepth = path.diffuseDepth;
  inputs.glossyDepth = path.glossyDepth;
  inputs.transmissionDepth = path.transmissionDepth;
#ifdef MG_CLOSURE_CHOICE
  // A path's hit replaces it with its vertex's word (setClosureSeed); a shadow ray's hit and
  // a light sample's emitter keep this hash of the hit's distance and position, which both
  // architectures compute alike and which varies from sample to sample.
  inputs.closureSeed = pcgHash(floatBitsToUint(rayLength) ^
                               pcgHash(floatBitsToUint(inputs.position.v.x) ^
                                       pcgHash(floatBitsToUint(inputs.position.v.y))));
#else
  inputs.closureSeed = 0u;  // no graph of the scene calls ChooseShader
#endif
#endif
}

// The per-hit random word ChooseShader picks a shader by (MaterialInputs::closureSeed): the
// path vertex's key (rng.glsl: pixel, sample, vertex, seed), hashed apart from the numbers the
// vertex draws for its light and BSDF samples, so both architectures choose alike and the
// path's own numbers are those it draws without a choice. A shadow ray's hit and a light
// sample's emitter, which have no vertex of their own, keep setPathInputs' word.
// Only where MaterialInputs has the path state (the callers test MG_OMIT_PATH_INPUTS too), and
// a hash only in scenes whose graphs choose (MG_CLOSURE_CHOICE): the others' kernels do no
// more work than without it.
#ifndef MG_OMIT_PATH_INPUTS
void setClosureSeed(inout MaterialInputs inputs, uint pixelIndex, uint sampleIndex,
                    uint vertexKey, uint seed) {
#ifdef MG_CLOSURE_CHOICE
  inputs.closureSeed =
      pcgHash(rngForPathVertex(pixelIndex, sampleIndex, vertexKey, seed).key ^ 0xBB67AE85u);
#endif
}
#endif

// The power heuristic (beta 2) for a sample of pdf a against a strategy of pdf b.
float misWeight(float a, float b) {
  float a2 = a * a;
  float b2 = b * b;
  return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

// One light sample of a shading point: the direction towards the light, the shadow ray's
// length, and the radiance it brings over its pdf. An emissive triangle's (lightPdf > 0) is
// MIS-weighted against BSDF sampling; with `evaluate` its emission is still to be taken
// from the material's graph at `hit`.
struct LightSample {
  vec3 wi;
  float tMax;
  vec3 incident;   // L_i / pdf (an emitter to evaluate: 1 / pdf, times its emission later)
  float lightPdf;  // solid-angle pdf of an emissive-triangle sample; 0 for punctual lights
  bool evaluate;
#ifdef MG_EMISSIVE_NEE
  HitInfo hit;     // the triangle point, where `evaluate` needs it
#endif
};

#ifdef MG_EMISSIVE_NEE
// Emissive-triangle NEE (docs/design/path-tracer.md): one emissive triangle chosen by power (CDF in
// the light buffer) and a uniform point on it. Its emission is the triangle record's
// constant where the host knows the material emits one colour everywhere (no material
// evaluation, so no second material call site in the kernel); otherwise the graph is
// evaluated at the point once the shadow ray found it unblocked, a call site compiled in
// only for scenes with such emitters (MG_NEE_EVALUATES_EMISSION). False: no contribution.
bool sampleEmissiveTriangle(vec3 position, uint first, uint count, float u, inout Rng rng,
                            out LightSample s) {
  uint lo = 0u;
  uint hi = count - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (lights[first + mid].intensity.x < u) lo = mid + 1u;
    else hi = mid;
  }
  Light tri = lights[first + lo];
  s.hit.instanceIndex = floatBitsToUint(tri.spot.x);
  s.hit.primitiveIndex = floatBitsToUint(tri.spot.y);
  vec2 r = rngNext2(rng);
  float su = sqrt(r.x);
  s.hit.barycentrics = vec2(su * (1.0 - r.y), su * r.y);
  Instance instance = instances[s.hit.instanceIndex];
  Mesh mesh = meshes[instance.ids.x];
  uint firstIndex = mesh.ranges.y + 3u * s.hit.primitiveIndex;
  mat4 toWorld = instance.objectToWorld;
  vec3 p0 = (toWorld * vec4(vertices[mesh.ranges.x + indices[firstIndex]].position.xyz, 1.0)).xyz;
  vec3 p1 =
      (toWorld * vec4(vertices[mesh.ranges.x + indices[firstIndex + 1u]].position.xyz, 1.0)).xyz;
  vec3 p2 =
      (toWorld * vec4(vertices[mesh.ranges.x + indices[firstIndex + 2u]].position.xyz, 1.0)).xyz;
  vec3 target = (1.0 - s.hit.barycentrics.x - s.hit.barycentrics.y) * p0 +
                s.hit.barycentrics.x * p1 + s.hit.barycentrics.y * p2;
  vec3 toLight = target - position;
  float d2 = dot(toLight, toLight);
  if (!(d2 > 1e-12)) return false;
  float distance = sqrt(d2);
  s.wi = toLight / distance;
  s.tMax = distance * (1.0 - 1e-3);
  s.hit.t = distance;
  vec3 lightNormal = cross(p1 - p0, p2 - p0);
  float cosLight = abs(dot(normalize(lightNormal), s.wi));
  float areaPdf = instance.objectInfo.y;
  if (cosLight < 1e-6 || !(areaPdf > 0.0)) return false;
  // A one-sided constant emitter (an area lamp) seen from behind.
  if (tri.spotSmooth.w == 2.0 && dot(lightNormal, toLight) >= 0.0) return false;
  s.lightPdf = areaPdf * d2 / cosLight;  // area to solid angle
  s.evaluate = tri.spotSmooth.w == 0.0;
  s.incident = (s.evaluate ? vec3(1.0) : tri.spotSmooth.xyz) / s.lightPdf;
  return true;
}
#endif

// A point, spot or directional light chosen uniformly (u in [0,1)). False: no contribution.
bool samplePunctualLight(vec3 position, uint count, float u, out LightSample s) {
  Light light = lights[min(uint(u * float(count)), count - 1u)];
  s.lightPdf = 0.0;
  s.evaluate = false;
  uint lightType = uint(light.positionOrDirection.w);
  if (lightType == kLightDirectional) {
    s.wi = -normalize(light.positionOrDirection.xyz);
    s.tMax = kRayTMax;
    s.incident = light.intensity.rgb * float(count);  // irradiance perpendicular to the light
    return true;
  }
  vec3 toLight = light.positionOrDirection.xyz - position;
  float d2 = max(dot(toLight, toLight), 1e-12);
  float distance = sqrt(d2);
  s.wi = toLight / distance;
  s.tMax = distance * (1.0 - 1e-4);
  s.incident = light.intensity.rgb / d2 * float(count);  // radiant intensity over distance²
  if (lightType == kLightSpot) {
    // Cycles 3.4's spot_light_attenuation: the cosine to the axis, cut at the cone and
    // smoothstepped over the blend width.
    float attenuation = dot(-s.wi, light.spot.xyz);
    if (attenuation <= light.spot.w) return false;
    float t = attenuation - light.spot.w;
    float smoothWidth = light.spotSmooth.x;
    if (t < smoothWidth && smoothWidth != 0.0) attenuation *= smoothstep(0.0, smoothWidth, t);
    s.incident *= attenuation;
  }
  return true;
}
// The primary ray through a point of the pixel (jitter in [0,1)^2).
void primaryRay(uvec2 pixel, vec2 jitter, out vec3 origin, out vec3 direction) {
  vec2 size = vec2(frame.image.xy);
  vec2 ndc = (vec2(pixel) + jitter) / size * 2.0 - 1.0;
  origin = frame.cameraPosition.xyz;
  direction = normalize(frame.cameraForward.xyz + ndc.x * frame.cameraRight.xyz -
                        ndc.y * frame.cameraUp.xyz);
}


// A hit's shading frame: the material's normal (the geometric one where the graph wrote
// none, flipped to the ray's side), the basis around it, the outgoing direction and the BSDF.
struct ShadingPoint {
  vec3 position;
  vec3 geometricNormal;
  mat3 toLocal;
  vec3 wo;
  BrdfParameters brdf;
#ifdef MG_BSDF_LOBES
  BsdfLobes lobes;  // with count > 0 the BSDF (bsdf_lobes.glsl); brdf is then unused
#endif
  bool transmits;  // some lobe sends light through: light sampling looks on both sides
};

#ifdef MG_LOBE_NORMALS
// Each lobe's frame (bsdf_lobes.glsl BsdfLobes::toLobe): its own normal (lobeParameters z, w),
// flipped to the geometric normal's side as the material's normal is, with a basis around it,
// as a rotation from the material's frame `toLocal`; a lobe without one keeps the material's.
void bsdfLobesSetNormals(inout BsdfLobes lobes, MaterialOutputs m, mat3 toLocal,
                         vec3 geometricNormal) {
  lobes.anyOwnNormal = false;
  lobes.geometricNormal = toLocal * geometricNormal;
  for (int i = 0; i < MG_MAX_LOBES; ++i) {
    lobes.ownNormal[i] = i < lobes.count && lobeHasOwnNormal(m, i);
    lobes.toLobe[i] = mat3(1.0);
    if (!lobes.ownNormal[i]) continue;
    lobes.anyOwnNormal = true;
    vec3 n = lobeNormalDecode(m.lobeParameters[i].zw);
    if (dot(n, geometricNormal) < 0.0) n = -n;
    vec3 t, b;
    basisAround(n, t, b);
    lobes.toLobe[i] = transpose(mat3(t, b, n)) * transpose(toLocal);
  }
}
#endif

ShadingPoint shadingPointAt(SurfaceHit s, MaterialOutputs m, vec3 direction) {
  ShadingPoint p;
  vec3 n = dot(m.normal, m.normal) > 1e-30 ? normalize(m.normal) : s.geometricNormal;
  if (dot(n, s.geometricNormal) < 0.0) n = -n;
  vec3 t, b;
  basisAround(n, t, b);
  p.toLocal = transpose(mat3(t, b, n));
  p.wo = -direction;
  p.brdf = brdfFromMaterial(m.baseColor, m.metallic, m.roughness, m.specular, m.specularTint,
                            m.cyclesPrincipled);
  p.position = s.inputs.position.v;
  p.geometricNormal = s.geometricNormal;
#ifdef MG_BSDF_LOBES
  p.lobes = bsdfLobesFromMaterial(m, s.entering, p.brdf);
#ifdef MG_LOBE_NORMALS
  bsdfLobesSetNormals(p.lobes, m, p.toLocal, s.geometricNormal);
#endif
  p.transmits = p.lobes.count > 0 && bsdfLobesTransmit(p.lobes);
#else
  p.transmits = false;
#endif
  return p;
}

#ifdef MG_FILTER_GLOSSY_INVERSE
// Cycles 3.4's Filter Glossy (integrator/surface_shader.h surface_shader_prepare_closures,
// closure/bsdf.h bsdf_blur; scene/integrator.cpp keeps 1 / F, MG_FILTER_GLOSSY_INVERSE): at a
// hit whose path has bounced with a pdf as low as minRayPdf, blur_pdf = minRayPdf / F; below
// 1 every microfacet closure's alpha becomes max(alpha, sqrt(1 - blur_pdf) / 2): a small
// glossy highlight seen through a diffuse or rough bounce, which few paths would find, each
// bringing much, is spread over many that bring less (less noise, some bias). Microfacet here: the Glossy, Refraction and Glass lobes of GGX and Beckmann
// (Cycles' MICROFACET_GGX/BECKMANN ids, refraction and glass too; a smooth one, singular at
// alpha^2 <= 1e-7, turns rough as Cycles' does), the Principled BSDF's specular GGX (the BRDF
// of a material without lobes, and the Principled lobe's), its clearcoat (GGX_CLEARCOAT) and
// its transmission's reflection and refraction. Diffuse, Oren-Nayar, Velvet, Translucent,
// Transparent and the sheen keep theirs, as bsdf_blur's default case does. The lobes hold
// perceptual roughness (alpha = roughness^2, lobeAlpha), so their roughness takes the max
// with sqrt of the blur's alpha. A lobe of Blender's Sharp distribution (roughness slot
// MG_LOBE_ROUGHNESS_SHARP in the material's outputs `m`) is Cycles' separate perfect
// reflection or refraction closure, which bsdf_blur leaves alone. Applied per hit to the
// shading point, after the material's outputs (and any cache lookup of them), never stored.
void filterGlossy(inout ShadingPoint p, MaterialOutputs m, PathState path) {
  float blurPdf = MG_FILTER_GLOSSY_INVERSE * path.minRayPdf;
  if (!(blurPdf < 1.0)) return;
  float blurAlpha = sqrt(1.0 - blurPdf) * 0.5;
  p.brdf.alpha = max(p.brdf.alpha, blurAlpha);
#ifdef MG_BSDF_LOBES
  float blurRoughness = sqrt(blurAlpha);
  for (int i = 0; i < MG_MAX_LOBES; ++i) {
    if (i >= p.lobes.count) break;
    int kind = p.lobes.kind[i];
    if (m.lobeParameters[i].x < 0.0) continue;  // Sharp (MG_LOBE_ROUGHNESS_SHARP)
    if (kind == MG_LOBE_GLOSSY_GGX || kind == MG_LOBE_GLOSSY_BECKMANN || lobeIsRefraction(kind) ||
        lobeIsGlass(kind) || kind == MG_LOBE_PRINCIPLED || kind == MG_LOBE_PRINCIPLED_CLEARCOAT ||
        kind == MG_LOBE_PRINCIPLED_GLASS)
      p.lobes.roughness[i] = max(p.lobes.roughness[i], blurRoughness);
  }
#ifdef MG_PRINCIPLED_LAYERS
  p.lobes.principled.alpha = max(p.lobes.principled.alpha, blurAlpha);
  p.lobes.glassReflectionRoughness = max(p.lobes.glassReflectionRoughness, blurRoughness);
#endif
#endif
}
#endif

// The shading point's BSDF times the cosine (local frame): its lobes, or the Principled BRDF.
vec3 bsdfEvaluateCos(ShadingPoint p, vec3 wo, vec3 wi) {
#ifdef MG_BSDF_LOBES
  if (p.lobes.count > 0) return bsdfLobesEvaluateCos(p.lobes, wo, wi);
#endif
  return brdfEvaluateCos(p.brdf, wo, wi);
}

// The density with which continuePath samples wi (local frame).
float bsdfPdf(ShadingPoint p, vec3 wo, vec3 wi) {
#ifdef MG_BSDF_LOBES
  if (p.lobes.count > 0) return bsdfLobesPdf(p.lobes, wo, wi);
#endif
  return brdfPdf(p.brdf, wo, wi);
}

// The MIS weight of emission found by a BSDF ray of pdf `previousBsdfPdf` (0: a camera ray)
// against emissive NEE, which could have sampled the same point (power heuristic).
float emissionMisWeight(SurfaceHit s, vec3 origin, vec3 direction, float previousBsdfPdf) {
  float emissionWeight = 1.0;
#ifdef MG_EMISSIVE_NEE
  if (previousBsdfPdf > 0.0 && s.lightAreaPdf > 0.0) {
    vec3 toHit = s.inputs.position.v - origin;
    float cosLight = abs(dot(s.geometricNormal, direction));
    float lightPdf = cosLight > 1e-6 ? s.lightAreaPdf * dot(toHit, toHit) / cosLight : 0.0;
    emissionWeight = misWeight(previousBsdfPdf, lightPdf);
  }
#endif
  return emissionWeight;
}

// Where a ray towards wi leaves the shading point: off the surface on wi's side of the
// geometric normal (the far side for a transmitted direction), so that it does not find the
// surface it leaves.
vec3 rayOriginTowards(ShadingPoint p, vec3 wi) {
  return offsetRayOrigin(p.position,
                         dot(wi, p.geometricNormal) >= 0.0 ? p.geometricNormal : -p.geometricNormal);
}

// Whether wi lies on the same side of the geometric normal as of the shading normal (local
// wi.z): a direction between the two planes would leak light through the surface or hide it.
// Where a lobe has its own normal, each lobe checks its own (bsdf_lobes.glsl lobeDirections),
// and the material's normal, which then may shade no lobe, does not.
bool sameSideOfBothNormals(ShadingPoint p, vec3 wi, float wiLocalZ) {
  float g = dot(wi, p.geometricNormal);
#ifdef MG_LOBE_NORMALS
  if (p.lobes.count > 0 && p.lobes.anyOwnNormal) return true;
#endif
  return wiLocalZ > 0.0 ? g > 0.0 : g < 0.0;
}

// Direct light (thesis §5.2), up to its shadow ray: one light sample, with emissive triangles
// (MG_EMISSIVE_NEE) half the samples going to them and half to the point, spot and
// directional lights. False: no contribution, no shadow ray. `fCos`: the BSDF times the
// cosine towards the light; the caller traces the shadow ray from rayOriginTowards(p, s.wi)
// along s.wi up to s.tMax, then weights with lightSampleMisWeight. A light behind the
// surface is sampled only for a BSDF that transmits (Translucent, rough Refraction and
// Glass); singular lobes evaluate to 0, so a light is never seen through smooth glass or a
// Transparent lobe by light sampling (Cycles' light sampling cannot either). The shadow ray
// stops at any surface, except with MG_TRANSPARENT_SHADOWS at the surfaces of materials that
// may be transparent, which it passes tinted (transparent_shadow.glsl,
// docs/design/closures.md).
bool sampleLightBeforeShadowRay(ShadingPoint p, inout Rng rng, out LightSample s, out vec3 fCos) {
  fCos = vec3(0.0);
  uint lightCount = frame.path.w;
  if (lightCount == 0u) return false;
  float u = rngNext(rng);
#ifdef MG_EMISSIVE_NEE
  // The triangle records follow the punctual lights, and each holds both counts.
  Light lastLight = lights[lightCount - 1u];
  uint punctual = uint(lastLight.intensity.y);
  uint triangleCount = uint(lastLight.intensity.z);
  bool pickTriangle = punctual == 0u || u < 0.5;
  if (punctual > 0u) u = pickTriangle ? 2.0 * u : 2.0 * u - 1.0;
  bool found = pickTriangle ? sampleEmissiveTriangle(p.position, punctual, triangleCount, u, rng, s)
                            : samplePunctualLight(p.position, punctual, u, s);
  // A triangle's pdf already holds its group's 1/2 (SceneBuffers upload); a punctual one's not
  // (here punctual > 0, since the pick chose it).
  if (!pickTriangle) s.incident *= 2.0;
#else
  bool found = samplePunctualLight(p.position, lightCount, u, s);
#endif
  if (!found) return false;
  vec3 wiLocal = p.toLocal * s.wi;
  if (!p.transmits && dot(s.wi, p.geometricNormal) <= 0.0) return false;
  if (!sameSideOfBothNormals(p, s.wi, wiLocal.z)) return false;
  fCos = bsdfEvaluateCos(p, p.toLocal * p.wo, wiLocal);
  if (all(equal(fCos, vec3(0.0)))) return false;
  return true;
}

// The light sample's MIS weight against BSDF sampling (power heuristic): an emissive
// triangle's when `mis` (the path continues, so a BSDF ray can find the same emitter); 1 for
// punctual lights and at a path's last vertex.
float lightSampleMisWeight(LightSample s, ShadingPoint p, bool mis) {
#ifdef MG_EMISSIVE_NEE
  if (s.lightPdf > 0.0 && mis)
    return misWeight(s.lightPdf, bsdfPdf(p, p.toLocal * p.wo, p.toLocal * s.wi));
#endif
  return 1.0;
}

#ifdef MG_BSDF_LOBES
// continuePath for a material of BSDF lobes (bsdf_lobes.glsl bsdfLobesSample): one lobe
// picked by uLobe, a direction drawn from it, the throughput weighted by the whole BSDF over
// the mixture's pdf (a singular lobe's by its own weight). A direction through the surface
// leaves from its far side; a singular one leaves previousBsdfPdf 0, so that the emission it
// finds is taken whole (light sampling could not find it), as Cycles' MIS skips it.
bool continuePathThroughLobes(ShadingPoint p, SurfaceHit s, vec3 woLocal, float uLobe,
                              inout Rng rng, inout vec3 throughput, inout float previousBsdfPdf,
                              inout RayCone cone, inout vec3 origin, inout vec3 direction,
                              inout PathState path) {
  vec2 u = rngNext2(rng);
  vec3 wiLocal, weight;
  float pdf;
  BsdfLobe sampled;
  bool diffuse;
  if (!bsdfLobesSample(p.lobes, woLocal, uLobe, u, wiLocal, weight, pdf, sampled, diffuse))
    return false;
  vec3 wi = transpose(p.toLocal) * wiLocal;
  if (!sameSideOfBothNormals(p, wi, wiLocal.z)) return false;
  throughput *= weight;
  previousBsdfPdf = pdf;
#ifdef MG_FILTER_GLOSSY_INVERSE
  pathStateAfterBsdfPdf(path, pdf);
#endif
  int kind = sampled.kind;
  float roughness = sampled.roughness;
  bool transmitted = wiLocal.z < 0.0;
#ifdef MG_LOBE_NORMALS
  // The lobe's side is the geometric normal's (lobeDirections), not the material normal's.
  if (p.lobes.anyOwnNormal) transmitted = dot(wi, s.geometricNormal) < 0.0;
#endif
  if (kind != MG_LOBE_TRANSPARENT) {  // a straight-through ray keeps its cone's spread
    cone.spread += rayConeRoughnessSpread(diffuse ? 1.0 : lobeAlpha(roughness)) +
                   rayConeCurvatureSpread(s.curvature, s.coneWidth, s.geometricNormal, direction);
    cone.spread = min(cone.spread, kRayConeMaxSpread);
  }
  cone.width = s.coneWidth;
  origin = rayOriginTowards(p, wi);
  direction = wi;
  if (kind == MG_LOBE_TRANSPARENT) return true;  // Cycles' transparent bounce: no depth
  if (transmitted)
    pathStateAfterTransmission(path, diffuse, lobeIsSingular(kind, roughness));
  else
    pathStateAfterReflection(path, !diffuse, roughness);
  return true;
}
#endif

// BRDF importance sampling of the next direction (eq. 2.9 with the lobe mixture): the
// throughput, the pdf (for the next hit's MIS), the ray cone (eq. 2.11, 2.12), the ray and
// the path state (the sampled lobe: Light Path) leave with it. False: the path ends here (no
// direction above the surface).
bool continuePath(ShadingPoint p, SurfaceHit s, inout Rng rng, inout vec3 throughput,
                  inout float previousBsdfPdf, inout RayCone cone, inout vec3 origin,
                  inout vec3 direction, inout PathState path) {
  vec3 woLocal = p.toLocal * p.wo;
  float uLobe = rngNext(rng);
#ifdef MG_BSDF_LOBES
  if (p.lobes.count > 0)
    return continuePathThroughLobes(p, s, woLocal, uLobe, rng, throughput, previousBsdfPdf, cone,
                                    origin, direction, path);
#endif
  vec3 wiLocal = brdfSample(p.brdf, woLocal, uLobe, rngNext2(rng));
  float pdf = brdfPdf(p.brdf, woLocal, wiLocal);
  vec3 wi = transpose(p.toLocal) * wiLocal;
  if (pdf <= 0.0 || dot(wi, s.geometricNormal) <= 0.0) return false;
  throughput *= brdfEvaluateCos(p.brdf, woLocal, wiLocal) / pdf;
  previousBsdfPdf = pdf;
#ifdef MG_FILTER_GLOSSY_INVERSE
  pathStateAfterBsdfPdf(path, pdf);
#endif

  // The cone leaves with its width and a spread grown by roughness (eq. 2.11) and
  // curvature (eq. 2.12); a diffuse bounce spreads like the roughest lobe.
  bool specularLobe = uLobe < brdfSpecularProbability(p.brdf, woLocal);
  cone.spread += rayConeRoughnessSpread(specularLobe ? p.brdf.alpha : 1.0) +
                 rayConeCurvatureSpread(s.curvature, s.coneWidth, s.geometricNormal, direction);
  cone.spread = min(cone.spread, kRayConeMaxSpread);
  cone.width = s.coneWidth;
  origin = offsetRayOrigin(p.position, s.geometricNormal);
  direction = wi;
  pathStateAfterReflection(path, specularLobe, p.brdf.roughness);
  return true;
}
