// Ray cones (thesis §2.2, after Akenine-Möller et al. 2021): a cone's width and spread
// angle travel with a path and give each hit an elliptical footprint, from which the UV
// and position derivatives that the material graph and textureGrad need are computed.

struct RayCone {
  float width;   // w: width at the last surface interaction (0 for primary rays)
  float spread;  // alpha: opening angle
};

// Eq. 2.10: width at a hit at distance t (small-angle approximation).
float rayConeWidthAt(RayCone cone, float t) {
  return cone.width + cone.spread * t;
}

// Eq. 2.11: spread added by a GGX lobe of roughness alpha, bounded. The root of eq. 2.11 is
// sigma = alpha / sqrt(2 - 2 alpha^2), the lobe's width as a slope (a tangent), and eq. 2.11
// (Akenine-Möller et al. 2021, "Improved Shader and Texture Level of Detail Using Ray
// Cones", JCGT 10(1), §4) uses it as an angle: beta = 2 sigma, the small-angle form. That
// diverges as alpha -> 1 (14 rad at the 0.99 clamp this code had), so after one diffuse
// bounce every texture fell to its coarsest mip and the cache level went strongly negative.
// Here the slope is turned into an angle, beta = 2 atan(sigma): the same for small alpha
// (atan x = x - x^3/3), and at most pi, a lobe over the whole hemisphere (alpha = 1, the
// diffuse bounce), which no physical cone can exceed.
float rayConeRoughnessSpread(float alphaGgx) {
  float a = clamp(alphaGgx, 0.0, 1.0);
  return 2.0 * atan(a, sqrt(max(2.0 - 2.0 * a * a, 0.0)));
}

// The most a cone may open: a hemisphere (pi). Spreads add up over bounces (alpha_new =
// alpha_old + beta_r + beta_c); past pi the small-angle width of eq. 2.10 means nothing.
const float kRayConeMaxSpread = 3.14159265;

// Eq. 2.12: spread added by a surface of curvature k for a cone of width w arriving along d.
float rayConeCurvatureSpread(float k, float width, vec3 normal, vec3 d) {
  float nd = dot(normal, d);
  if (abs(nd) < 1e-4) return 0.0;
  return -2.0 * k * width / nd;
}

// Curvature of a triangle from how its vertex normals turn along its edges: k = dn.e/|e|^2,
// averaged over the edges (0 for flat triangles).
float triangleCurvature(vec3 p0, vec3 p1, vec3 p2, vec3 n0, vec3 n1, vec3 n2) {
  vec3 e0 = p1 - p0;
  vec3 e1 = p2 - p1;
  vec3 e2 = p0 - p2;
  float k0 = dot(n1 - n0, e0) / max(dot(e0, e0), 1e-20);
  float k1 = dot(n2 - n1, e1) / max(dot(e1, e1), 1e-20);
  float k2 = dot(n0 - n2, e2) / max(dot(e2, e2), 1e-20);
  return (k0 + k1 + k2) / 3.0;
}

vec3 projectOnPlane(vec3 v, vec3 n) {
  return v - dot(v, n) * n;
}

// Eq. 2.13-2.16: offsets from the hit P to a vertex P1 and a co-vertex P2 of the footprint
// ellipse of a cone of width w along d on a surface with geometric normal n. The semi-axes
// are scaled by 2 (r = w instead of w/2) so that, as in rasterization, a derivative spans
// one whole pixel footprint and textureGrad picks the mip level a raster pipeline would.
void rayConeEllipseAxes(vec3 d, vec3 n, float w, out vec3 axis1, out vec3 axis2) {
  vec3 h1 = projectOnPlane(d, n);  // eq. 2.13
  if (dot(h1, h1) < 1e-12) {
    // Head-on: every direction in the plane is an axis; take any.
    h1 = abs(n.x) < 0.9 ? cross(n, vec3(1.0, 0.0, 0.0)) : cross(n, vec3(0.0, 1.0, 0.0));
  }
  h1 = normalize(h1);
  vec3 h2 = cross(n, h1);  // eq. 2.14
  float r = w;
  axis1 = h1 * r / max(length(projectOnPlane(h1, d)), 1e-4);  // eq. 2.15
  axis2 = h2 * r / max(length(projectOnPlane(h2, d)), 1e-4);  // eq. 2.16
}

// Barycentric coordinates (of vertices 1 and 2) of a point q in the plane of a triangle.
vec2 barycentricsOf(vec3 q, vec3 p0, vec3 p1, vec3 p2) {
  vec3 e1 = p1 - p0;
  vec3 e2 = p2 - p0;
  vec3 v = q - p0;
  float d11 = dot(e1, e1);
  float d12 = dot(e1, e2);
  float d22 = dot(e2, e2);
  float v1 = dot(v, e1);
  float v2 = dot(v, e2);
  float det = d11 * d22 - d12 * d12;
  if (abs(det) < 1e-30) return vec2(0.0);
  return vec2(d22 * v1 - d12 * v2, d11 * v2 - d12 * v1) / det;
}
