// Counter-based random numbers from the PCG hash (O'Neill 2014), so a pixel's numbers never
// depend on other pixels or on the order threads run in.

// PCG-hash of one 32-bit word (the RXS-M-XS output of a PCG step).
uint pcgHash(uint value) {
  uint state = value * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Every number is a hash of (pixel, sample, bounce, dimension), with no state carried from
// one bounce to the next. Both architectures draw from it with the same keys: the wavefront's
// passes (wavefront.glsl) need a path's numbers not to depend on the order in which the
// queues process paths (Laine, Karras and Aila, "Megakernels Considered Harmful", HPG 2013,
// keep per-path state in memory; here the generator needs only the key), and the megakernel
// (path_tracer.glsl) uses the same keys, so at one seed the two trace the same paths and
// their pictures agree per pixel, not only in the mean.
struct Rng {
  uint key;        // hash of pixel, sample (frame and path), bounce and seed
  uint dimension;  // the next number's index along this bounce
};

// The pixel's sample index over frames: frame * P + path (P paths a pixel a frame).
uint rngSampleIndex(uint frameIndex, uint pathsPerFrame, uint path) {
  return frameIndex * max(pathsPerFrame, 1u) + path;
}

// The generator of one bounce of one path; `sampleIndex` counts the pixel's samples over
// frames (rngSampleIndex), `bounce` 0 is the camera ray's (its pixel jitter) and bounce
// b + 1 the shading of the path's b-th hit (light sample, then the BSDF sample).
Rng rngForPathVertex(uint pixelIndex, uint sampleIndex, uint bounce, uint seed) {
  Rng rng;
  rng.key = pcgHash(pixelIndex ^ pcgHash(sampleIndex ^ pcgHash(bounce ^ pcgHash(seed))));
  rng.dimension = 0u;
  return rng;
}

// A uniform float in [0, 1): the hash of the key and the dimension, 24 random mantissa bits.
float rngNext(inout Rng rng) {
  uint word = pcgHash(rng.key ^ pcgHash(rng.dimension));
  rng.dimension += 1u;
  return float(word >> 8u) * (1.0 / 16777216.0);
}

vec2 rngNext2(inout Rng rng) {
  float a = rngNext(rng);
  return vec2(a, rngNext(rng));
}
