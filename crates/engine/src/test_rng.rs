//! A small deterministic generator for the engine's unit tests (xorshift64), so that
//! randomised checks are reproducible without a dependency.

/// Uniform numbers in [0, 1) from a fixed seed.
pub struct Xorshift(u64);

impl Xorshift {
    pub fn new(seed: u64) -> Xorshift {
        Xorshift(seed)
    }

    /// The next number in [0, 1).
    pub fn next(&mut self) -> f64 {
        let s = &mut self.0;
        *s ^= *s << 13;
        *s ^= *s >> 7;
        *s ^= *s << 17;
        (*s >> 11) as f64 / (1u64 << 53) as f64
    }
}
