// Blender's Bevel node, traced by the path tracer before the graph runs (a traced input,
// docs/design/traced-inputs.md), as Cycles 3.4's svm_bevel does it: points of a disk of
// Radius about the hit, on a plane picked among its three local axes, are projected onto the
// object's own surfaces along that axis, and the surfaces' normals there are averaged,
// weighted by a cubic falloff with distance and by multiple importance over the three axes
// (King, Kulla, Conty and Fajardo, "BSSRDF Importance Sampling", SIGGRAPH 2013 talk). Needs
// the trace backend's traceClosest, scene_bindings.glsl, rng.glsl and path_shading.glsl's
// basisAround and offsetRayOrigin first.

// Hits of the hit's own instance one disk ray weighs (Cycles' LOCAL_MAX_HITS), and the
// closest hits it walks through to find them (other instances' included).
const uint kBevelLocalHits = 4u;
const uint kBevelWalkSteps = 8u;

// The cubic falloff's density over the disk of radius R: 10 (R - r)^3 / (pi R^5) inside,
// 0 outside (it integrates to 1 over the disk).
float bevelCubicPdf(float radius, float r) {
  if (r >= radius) return 0.0;
  float f = radius - r;
  return 10.0 * f * f * f / (kPi * radius * radius * radius * radius * radius);
}

// A radius of the cubic falloff from u in [0,1): the root x of its radial CDF
// 10x^2 - 20x^3 + 15x^4 - 4x^5 = u (x = r / R, no closed form), by Newton's method.
float bevelCubicRadius(float radius, float u) {
  float x = 0.25;
  for (int i = 0; i < 10; ++i) {
    float x2 = x * x;
    float cdf = 10.0 * x2 - 20.0 * x2 * x + 15.0 * x2 * x2 - 4.0 * x2 * x2 * x - u;
    float slope = 20.0 * x * (1.0 - x) * (1.0 - x) * (1.0 - x);
    if (abs(cdf) < 1e-6 || slope == 0.0) break;
    x = clamp(x - cdf / slope, 0.0, 1.0);
  }
  return x * radius;
}

// Tangents across unit `n` as Cycles' make_orthonormals picks them: the first from the
// differences of n's components (orthogonal to n: their sum of products with n is 0), so for
// a face along the axes the tangents run diagonally. Bevel's estimate depends on its disks'
// axes, so memograph takes the same ones (any other basis biases the edges differently: the
// Duff basis gave a top edge 7 % off Cycles').
void bevelTangents(vec3 n, out vec3 t, out vec3 b) {
  t = (n.x != n.y || n.x != n.z) ? vec3(n.z - n.y, n.x - n.z, n.y - n.x)
                                 : vec3(n.z - n.y, n.x + n.z, -n.y - n.x);
  t = normalize(t);
  b = cross(n, t);
}

// The world-space smooth normal of `hit` and its face normal, both on the side the mesh's
// winding calls the front (as Cycles' hit normals, before any facing flip).
void bevelHitNormals(HitInfo hit, out vec3 smoothNormal, out vec3 faceNormal) {
  Instance instance = instances[hit.instanceIndex];
  Mesh mesh = meshes[instance.ids.z];
  uint firstIndex = mesh.ranges.y + 3u * hit.primitiveIndex;
  Vertex v0 = vertices[mesh.ranges.x + indices[firstIndex]];
  Vertex v1 = vertices[mesh.ranges.x + indices[firstIndex + 1u]];
  Vertex v2 = vertices[mesh.ranges.x + indices[firstIndex + 2u]];
  mat4 toWorld = instance.objectToWorld;
  vec3 p0 = (toWorld * vec4(v0.position.xyz, 1.0)).xyz;
  vec3 p1 = (toWorld * vec4(v1.position.xyz, 1.0)).xyz;
  vec3 p2 = (toWorld * vec4(v2.position.xyz, 1.0)).xyz;
  vec3 ng = cross(p1 - p0, p2 - p0);
  ng = dot(ng, ng) > 1e-30 ? normalize(ng) : vec3(0.0);
  faceNormal = determinant(mat3(toWorld)) < 0.0 ? -ng : ng;
  vec3 w = vec3(1.0 - hit.barycentrics.x - hit.barycentrics.y, hit.barycentrics);
  mat3 normalToWorld = mat3(instance.normalToWorld);
  vec3 n = w.x * v0.normal.xyz + w.y * v1.normal.xyz + w.z * v2.normal.xyz;
  n = normalToWorld * n;
  smoothNormal = dot(n, n) > 1e-30 ? normalize(n) : faceNormal;
}

// The Bevel normal at `position` of instance `instance` (shading normal `normal` and
// geometric normal `geometricNormal`, both facing the ray): `samples` disk rays within
// `radius`, on the ray's side of the surface. Where no ray finds the surface, `normal`.
vec3 bevelNormal(vec3 position, vec3 normal, vec3 geometricNormal, uint instance, float radius,
                 uint samples, inout Rng rng, inout uint rays) {
  if (!(radius > 0.0) || samples == 0u) return normal;
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < samples; ++i) {
    vec2 u = rngNext2(rng);
    // The disk's axis: the geometric normal half the time, each tangent a quarter.
    vec3 axisN = geometricNormal, axisT, axisB;
    bevelTangents(axisN, axisT, axisB);
    float pickN = 0.5, pickT = 0.25, pickB = 0.25;
    if (u.x < 0.5) {
      u.x *= 2.0;
    } else if (u.x < 0.75) {
      vec3 t = axisN;
      axisN = axisT;
      axisT = t;
      pickN = 0.25;
      pickT = 0.5;
      u.x = (u.x - 0.5) * 4.0;
    } else {
      vec3 t = axisN;
      axisN = axisB;
      axisB = t;
      pickN = 0.25;
      pickB = 0.5;
      u.x = (u.x - 0.75) * 4.0;
    }
    float diskR = bevelCubicRadius(radius, u.y);
    float height = sqrt(max(0.0, radius * radius - diskR * diskR));
    float phi = 2.0 * kPi * u.x;
    vec3 origin = position + height * axisN + diskR * (cos(phi) * axisT + sin(phi) * axisB);
    vec3 d = -axisN;
    float tMax = 2.0 * height;
    // Walk the ray's closest hits, keeping the own instance's (Cycles intersects the object
    // alone and keeps a random 4 of its hits; here the first 4, weighted the same way).
    float travelled = 0.0;
    uint ownHits = 0u;
    vec3 hitSum = vec3(0.0);
    for (uint step = 0u; step < kBevelWalkSteps && travelled < tMax; ++step) {
      rays += 1u;
      HitInfo hit = traceClosest(origin, d, tMax - travelled, kRayMaskNoLightQuads);
      if (hit.t < 0.0) break;
      vec3 hitPosition = origin + hit.t * d;
      travelled += hit.t;
      origin = offsetRayOrigin(hitPosition, d);
      if (hit.instanceIndex != instance) continue;
      ownHits += 1u;
      if (ownHits > kBevelLocalHits) continue;
      vec3 smoothN, faceN;
      bevelHitNormals(hit, smoothN, faceN);
      float pdfN = pickN * abs(dot(axisN, faceN));
      float pdfT = pickT * abs(dot(axisT, faceN));
      float pdfB = pickB * abs(dot(axisB, faceN));
      // The power heuristic over the three axes (pdfN cancels against the estimator's own).
      float weight = pdfN / max(pdfN * pdfN + pdfT * pdfT + pdfB * pdfB, 1e-20);
      float diskPdf = bevelCubicPdf(radius, diskR);
      weight *= diskPdf > 0.0 ? bevelCubicPdf(radius, length(hitPosition - position)) / diskPdf
                              : 0.0;
      hitSum += weight * smoothN;
    }
    if (ownHits > kBevelLocalHits) hitSum *= float(ownHits) / float(kBevelLocalHits);
    sum += hitSum;
  }
  if (!(dot(sum, sum) > 1e-30)) return normal;
  vec3 n = normalize(sum);
  // The hit normals are the mesh's front; the input faces the ray, as the shading normal.
  return dot(n, geometricNormal) < 0.0 ? -n : n;
}
