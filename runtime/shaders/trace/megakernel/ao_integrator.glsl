// The AO integrator (--integrator ao; seeds/004 §3, the ray-traced AO workload): each of a
// pixel's P paths is a jittered primary ray and, at its hit, MG_AO_SAMPLES rays of length
// MG_AO_DISTANCE_BITS (float bits) about the geometric normal facing the camera; the pixel
// holds the mean unoccluded fraction in r, g and b. A primary ray that finds nothing gives 1:
// nothing occludes the sky. Included by path_tracer.glsl in tracePixel's place.

// The mean unoccluded fraction over this dispatch's share of the pixel's P paths (the
// caller's running mean adds the shares, as tracePixel's).
float ambientOcclusionPixel(uvec2 pixel, bool inside, inout uint rays) {
  uint pathCount = max(frame.path.x, 1u);
  float sum = 0.0;
  if (!inside) return 0.0;
  for (uint path = 0u; path < pathCount; ++path) {
    if (!dispatchTracesPath(path, pathCount)) continue;
    uint pixelIndex = pixel.y * frame.image.x + pixel.x;
    uint sampleIndex = rngSampleIndex(frame.image.z, pathCount, path);
    Rng rng = rngForPathVertex(pixelIndex, sampleIndex, 0u, frame.image.w);
    vec3 origin, direction;
    primaryRay(pixel, rngNext2(rng), origin, direction);
    HitInfo hit = traceClosest(origin, direction, kRayTMax, kRayMaskNoLightQuads);
    rays += 1u;
    if (hit.t < 0.0) {
      sum += 1.0;
      continue;
    }
    RayCone cone;
    cone.width = 0.0;
    cone.spread = frame.cameraPosition.w;
    SurfaceHit s = surfaceAt(hit, origin, direction, cone);
    sum += ambientOcclusionIntegratorAt(s, pixelIndex, sampleIndex, rays);
  }
  return sum / float(pathCount);
}
