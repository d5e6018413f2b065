// The comparison runs' methods: ONE line per method. Shared by the bench (emu/src/main.rs) and
// the host check (emu/host_hash, which includes this file), so both render with the same
// renderers. Scenes: zrow-scenes' `foley100` and `foley2500` (Foley & van Dam's Table 15.3 at
// 100 and 2,500 polygons, 240 × 240, screen space), Q16.16 only.
//
// Capacities fit `foley2500` (measured: 2,498 polygons on screen, 6,356 edges, 230 active in
// one row; depth-sort makes 958 pieces by splitting, BSP 14,310) with room to spare.

/// Polygon capacity.
const FP: usize = 2_500;
/// Edge capacity.
const FE: usize = 7_500;
/// Active-list capacity (scan-line).
const FA: usize = 320;
/// Warnock's list capacity at bands of 16 rows: `n·(log2(16) + 2)` for the `n` polygons
/// reaching the busiest band, with room to spare.
const FL: usize = 6 * FP;

/// Calls `$run!(TYPE)` for every compared method, in report order.
macro_rules! for_each_method {
    ($run:ident) => {
        $run!(zrow::depthsort::DepthSort<Q16_16, 240, FP, FE, 4_096>);
        $run!(zrow::ZBuffer<Q16_16, 240, 240>);
        $run!(zrow::Scanline<Q16_16, 240, FE, FP, FA>);
        $run!(zrow::bsp::Bsp<Q16_16, 240, FP, FE, 20_480, 8_192>);
        $run!(zrow::abuffer::ABuffer<Q16_16, 240, FP, FE, 16>);
        $run!(zrow::tiled::Tiled<Q16_16, 240, 16, FP, FE>);
        $run!(zrow::warnock::Warnock<Q16_16, 240, 16, FP, FE, FL>);
    };
}

/// Calls `$run!(TYPE, FORMAT, SCENES)` (one renderer of the type for the scenes, in order) for
/// the cheap methods `auto` picks where a scene's structure allows (zrow::structure):
/// back-face culling alone on the cube, one closed convex solid (compare with the scan-line
/// lines for the same scene); then the scan-line method smooth shading the torus
/// (zrow-scenes' `SMOOTH`: `mesh1k-smooth`, compare with `mesh1k`, and `mesh1k-dither`).
macro_rules! for_each_structured {
    ($run:ident) => {
        $run!(zrow::cullonly::CullOnly<Q16_16, 240, 64, 256>, Q16_16, ["cube"]);
        $run!(zrow::cullonly::CullOnly<f32, 240, 64, 256>, f32, ["cube"]);
        $run!(Smooth<Q16_16>, Q16_16, zrow_scenes::SMOOTH);
        $run!(Smooth<f32>, f32, zrow_scenes::SMOOTH);
    };
}

/// The hidden-line sink the hidden-line scenes' frames (zrow-scenes' `LINES`: `mesh1k-lines`,
/// drawn after the structured ones by the standard renderer) go through: 240-pixel rows, into
/// the hash.
type Lines = zrow::lines::HiddenLines<FrameHash, 240>;


/// The scan-line renderer for smooth shading (`zrow_scenes::SMOOTH`): capacities for the
/// torus with room to spare (it needs 500 vertex slots, 454 polygons, 67 active), no affine
/// cue state, an intensity plane per polygon (`zrow::scanline_for!(N, REQ, gouraud)`).
type Smooth<N> =
    zrow::Scanline<N, 240, 1024, 512, 128, u16, zrow::scanline::Uncued, [zrow::IntensityPlane<N>; 512]>;
