// Counter-based random numbers: PCG (O'Neill 2014) seeded from pixel, frame and seed, so a
// pixel's sequence never depends on other pixels or on the order threads run in.

// PCG-hash of one 32-bit word (the RXS-M-XS output of a PCG step).
uint pcgHash(uint value) {
  uint state = value * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

#ifdef MG_RNG_COUNTER_BASED
// The wavefront passes' generator (wavefront.glsl): every number is a hash of (pixel,
// sample, bounce, dimension), with no state carried from one pass to the next, so a path's
// numbers do not depend on the order in which the queues process paths (Laine, Karras and
// Aila, "Megakernels Considered Harmful", HPG 2013, keep per-path state in memory; here the
// generator needs only the key).
struct Rng {
  uint key;        // hash of pixel, sample (frame and path), bounce and seed
  uint dimension;  // the next number's index along this bounce
};

// The generator of one bounce of one path; `sampleIndex` counts the pixel's samples over
// frames (frame * P + path), `bounce` 0 is the camera ray's.
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
#else
struct Rng {
  uint state;
};

// The generator of one pixel in one frame for one seed.
Rng rngForPixel(uvec2 pixel, uint frame, uint seed) {
  Rng rng;
  rng.state = pcgHash(pixel.x ^ pcgHash(pixel.y ^ pcgHash(frame ^ pcgHash(seed))));
  return rng;
}

// A uniform float in [0, 1): one PCG32 step, 24 random mantissa bits.
float rngNext(inout Rng rng) {
  rng.state = rng.state * 747796405u + 2891336453u;
  uint word = ((rng.state >> ((rng.state >> 28u) + 4u)) ^ rng.state) * 277803737u;
  word = (word >> 22u) ^ word;
  return float(word >> 8u) * (1.0 / 16777216.0);
}
#endif

vec2 rngNext2(inout Rng rng) {
  float a = rngNext(rng);
  return vec2(a, rngNext(rng));
}
