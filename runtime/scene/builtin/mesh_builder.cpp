#include "runtime/scene/builtin/mesh_builder.h"

#include <cmath>
#include <numbers>

namespace memograph::runtime {
namespace {

// One quad from `origin` spanning `uAxis`·uLength and `vAxis`·vLength; uAxis × vAxis is the
// face normal, so the triangles wind counter-clockwise seen from outside.
void appendQuad(Mesh& mesh, glm::vec3 origin, glm::vec3 uAxis, float uLength, glm::vec3 vAxis,
                float vLength, UvScale uv) {
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  const glm::vec3 normal = glm::cross(uAxis, vAxis);
  const float s = 1.0f / uv.metresPerUnit;
  const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const glm::vec2 c : corners) {
    mesh.positions.push_back(origin + uAxis * (c.x * uLength) + vAxis * (c.y * vLength));
    mesh.normals.push_back(normal);
    mesh.uvs.push_back({c.x * uLength * s, c.y * vLength * s});
  }
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u})
    mesh.indices.push_back(base + i);
}

}  // namespace

void appendBox(Mesh& mesh, glm::vec3 mn, glm::vec3 mx, UvScale uv) {
  const glm::vec3 d = mx - mn;
  const glm::vec3 X{1, 0, 0}, Y{0, 1, 0}, Z{0, 0, 1};
  appendQuad(mesh, {mx.x, mn.y, mx.z}, -Z, d.z, Y, d.y, uv);  // +x
  appendQuad(mesh, {mn.x, mn.y, mn.z}, Z, d.z, Y, d.y, uv);   // -x
  appendQuad(mesh, {mn.x, mx.y, mx.z}, X, d.x, -Z, d.z, uv);  // +y
  appendQuad(mesh, {mn.x, mn.y, mn.z}, X, d.x, Z, d.z, uv);   // -y
  appendQuad(mesh, {mn.x, mn.y, mx.z}, X, d.x, Y, d.y, uv);   // +z
  appendQuad(mesh, {mx.x, mn.y, mn.z}, -X, d.x, Y, d.y, uv);  // -z
}

Mesh makeHeightfield(std::string name, float x0, float z0, float x1, float z1, int cells,
                     const std::function<float(float, float)>& height, UvScale uv) {
  Mesh mesh;
  mesh.name = std::move(name);
  const int n = cells + 1;
  const float dx = (x1 - x0) / cells, dz = (z1 - z0) / cells;
  const float s = 1.0f / uv.metresPerUnit;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const float x = x0 + i * dx, z = z0 + j * dz;
      mesh.positions.push_back({x, height(x, z), z});
      // Central differences of the height function itself, so normals are smooth across
      // the grid instead of faceted by it.
      const float hx = (height(x + dx, z) - height(x - dx, z)) / (2 * dx);
      const float hz = (height(x, z + dz) - height(x, z - dz)) / (2 * dz);
      mesh.normals.push_back(glm::normalize(glm::vec3(-hx, 1.0f, -hz)));
      mesh.uvs.push_back({x * s, z * s});
    }
  }
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const auto v00 = static_cast<std::uint32_t>(j * n + i);
      const std::uint32_t v10 = v00 + 1, v01 = v00 + n, v11 = v00 + n + 1;
      for (std::uint32_t v : {v00, v01, v11, v00, v11, v10})
        mesh.indices.push_back(v);
    }
  }
  computeTangents(mesh);
  return mesh;
}

void appendCylinder(Mesh& mesh, glm::vec3 base, float radius, float height, int segments,
                    UvScale uv) {
  const float s = 1.0f / uv.metresPerUnit;
  const float circumference = 2.0f * std::numbers::pi_v<float> * radius;
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  // Side: segments+1 columns so the seam gets its own UVs.
  for (int i = 0; i <= segments; ++i) {
    const float a = 2.0f * std::numbers::pi_v<float> * i / segments;
    const glm::vec3 dir{std::cos(a), 0.0f, -std::sin(a)};
    for (int k = 0; k < 2; ++k) {
      mesh.positions.push_back(base + dir * radius + glm::vec3(0, k * height, 0));
      mesh.normals.push_back(dir);
      mesh.uvs.push_back({circumference * i / segments * s, k * height * s});
    }
  }
  for (int i = 0; i < segments; ++i) {
    const std::uint32_t a = first + 2 * i, b = a + 2;
    for (std::uint32_t v : {a, b, b + 1, a, b + 1, a + 1})
      mesh.indices.push_back(v);
  }
  // Top cap: a fan; UV is planar in xz so the texel density matches the side.
  const auto centre = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.push_back(base + glm::vec3(0, height, 0));
  mesh.normals.push_back({0, 1, 0});
  mesh.uvs.push_back({0, 0});
  for (int i = 0; i <= segments; ++i) {
    const float a = 2.0f * std::numbers::pi_v<float> * i / segments;
    const glm::vec3 offset{std::cos(a) * radius, 0.0f, -std::sin(a) * radius};
    mesh.positions.push_back(base + glm::vec3(0, height, 0) + offset);
    mesh.normals.push_back({0, 1, 0});
    mesh.uvs.push_back({offset.x * s, -offset.z * s});
  }
  for (int i = 0; i < segments; ++i) {
    for (std::uint32_t v : {centre, centre + 1 + i, centre + 2 + i})
      mesh.indices.push_back(v);
  }
}

void appendCone(Mesh& mesh, glm::vec3 base, float radius, float height, int segments, UvScale uv) {
  const float s = 1.0f / uv.metresPerUnit;
  const float slant = std::sqrt(radius * radius + height * height);
  const float circumference = 2.0f * std::numbers::pi_v<float> * radius;
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  for (int i = 0; i <= segments; ++i) {
    const float a = 2.0f * std::numbers::pi_v<float> * i / segments;
    const glm::vec3 dir{std::cos(a), 0.0f, -std::sin(a)};
    // The side's normal tilts up by the cone's half-angle.
    const glm::vec3 normal = glm::normalize(dir * height + glm::vec3(0, radius, 0));
    mesh.positions.push_back(base + dir * radius);
    mesh.normals.push_back(normal);
    mesh.uvs.push_back({circumference * i / segments * s, 0.0f});
    mesh.positions.push_back(base + glm::vec3(0, height, 0));
    mesh.normals.push_back(normal);
    mesh.uvs.push_back({circumference * i / segments * s, slant * s});
  }
  for (int i = 0; i < segments; ++i) {
    const std::uint32_t a = first + 2 * i, b = a + 2;
    for (std::uint32_t v : {a, b, a + 1})
      mesh.indices.push_back(v);
  }
}

void appendDeformedSphere(Mesh& mesh, glm::vec3 centre, glm::vec3 radii, int rings, int segments,
                          const std::function<float(glm::vec3)>& radiusScale, UvScale uv) {
  const float s = 1.0f / uv.metresPerUnit;
  const float meanRadius = (radii.x + radii.y + radii.z) / 3.0f;
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  for (int r = 0; r <= rings; ++r) {
    const float theta = std::numbers::pi_v<float> * r / rings;
    for (int i = 0; i <= segments; ++i) {
      const float phi = 2.0f * std::numbers::pi_v<float> * i / segments;
      const glm::vec3 dir{std::sin(theta) * std::cos(phi), std::cos(theta),
                          -std::sin(theta) * std::sin(phi)};
      mesh.positions.push_back(centre + dir * radii * radiusScale(dir));
      mesh.normals.push_back(dir);  // replaced by computeNormals below
      mesh.uvs.push_back(
          {phi * meanRadius * s, (std::numbers::pi_v<float> - theta) * meanRadius * s});
    }
  }
  const int columns = segments + 1;
  for (int r = 0; r < rings; ++r) {
    for (int i = 0; i < segments; ++i) {
      const std::uint32_t a = first + r * columns + i, b = a + 1, c = a + columns, d = c + 1;
      for (std::uint32_t v : {a, c, d, a, d, b})
        mesh.indices.push_back(v);
    }
  }
  computeNormals(mesh);
}

void computeNormals(Mesh& mesh) {
  std::vector<glm::vec3> sum(mesh.positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    // The unnormalized cross product weighs each face by twice its area.
    const glm::vec3 n = glm::cross(mesh.positions[i1] - mesh.positions[i0],
                                   mesh.positions[i2] - mesh.positions[i0]);
    sum[i0] += n;
    sum[i1] += n;
    sum[i2] += n;
  }
  mesh.normals.resize(mesh.positions.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const float len = glm::length(sum[i]);
    // A vertex only on degenerate faces keeps the normal it had (or +y).
    if (len > 0.0f) {
      mesh.normals[i] = sum[i] / len;
    } else if (glm::length(mesh.normals[i]) == 0.0f) {
      mesh.normals[i] = {0, 1, 0};
    }
  }
}

void computeTangents(Mesh& mesh) {
  mesh.tangents.clear();
  if (mesh.uvs.size() != mesh.positions.size())
    return;
  std::vector<glm::vec3> tan(mesh.positions.size(), glm::vec3(0.0f));
  std::vector<glm::vec3> bitan(mesh.positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0];
    const glm::vec3 e2 = mesh.positions[i2] - mesh.positions[i0];
    const glm::vec2 d1 = mesh.uvs[i1] - mesh.uvs[i0];
    const glm::vec2 d2 = mesh.uvs[i2] - mesh.uvs[i0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-12f)
      continue;  // no UV area: says nothing about the frame
    // dP/du and dP/dv of the triangle, weighted by its UV area through `det`'s sign only.
    const float r = det > 0 ? 1.0f : -1.0f;
    const glm::vec3 dpdu = (e1 * d2.y - e2 * d1.y) * r;
    const glm::vec3 dpdv = (e2 * d1.x - e1 * d2.x) * r;
    for (std::uint32_t i : {i0, i1, i2}) {
      tan[i] += dpdu;
      bitan[i] += dpdv;
    }
  }
  mesh.tangents.resize(mesh.positions.size());
  for (std::size_t i = 0; i < tan.size(); ++i) {
    const glm::vec3 n = mesh.normals[i];
    glm::vec3 t = tan[i] - n * glm::dot(n, tan[i]);
    if (glm::length(t) < 1e-8f) {
      // Degenerate (a pole, or no UV area): any unit vector perpendicular to n.
      t = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0))
                               : glm::cross(n, glm::vec3(0, 1, 0));
    }
    t = glm::normalize(t);
    const float w = glm::dot(glm::cross(n, t), bitan[i]) < 0.0f ? -1.0f : 1.0f;
    mesh.tangents[i] = glm::vec4(t, w);
  }
}

}  // namespace memograph::runtime
