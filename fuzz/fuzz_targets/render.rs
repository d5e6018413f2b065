//! Any bytes → a scene (screen or model mode, Q16.16 or f32, any bit pattern for positions,
//! camera and transform, out-of-range indices, faces of 0..12 vertices, any alpha) → every
//! method at small capacities. The contract checked: no panic; rows arrive top to bottom, each
//! once, all of them on success and none on error (nothing drawn is corrupted).
//!
//! ```sh
//! cargo +nightly fuzz run render -- -max_total_time=600
//! ```
#![no_main]

mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    harness::check(data);
});
