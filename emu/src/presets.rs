// The preset runs: every named preset (`zrow::presets::PRESETS`) on every preset scene
// (`zrow_scenes::PRESET_SCENES`: cube, mesh1k, interlocked, 240 × 240, each built with the
// preset's maths and configured by `Preset::config`). Shared by the bench (emu/src/main.rs) and
// the host check (emu/host_hash, which includes this file), so both draw each preset with the
// same renderer type. Each includer defines `Standard<N>`, its scan-line renderer.
//
// A preset's `format` picks the number type (`preset_formats!` below) and its `store` the
// renderer: `DepthStore::Row32` draws with `Standard<N>` (the scan-line renderer the standard
// scenes use), `DepthStore::Tile16` with `PresetTiled<N>`.
//
// Capacities: the preset scenes need at most 454 polygons after back-face culling, 1,282 edges
// and 65 active polygons in one row (mesh1k; interlocked: 251, 733, 56), measured with
// `zrow::requirements` under every preset. `Standard<N>` (1,024 / 3,072 / 512) holds that;
// `PresetTiled<N>` is sized below with room to spare.

/// Polygon capacity of the presets' tiled renderer (454 needed).
const PP: usize = 640;
/// Edge capacity of the presets' tiled renderer (1,282 needed).
const PE: usize = 1_920;

/// The renderer of `DepthStore::Tile16` presets: bands of 16 rows, as the comparison runs'
/// `tiled` (src/methods.rs).
type PresetTiled<N> = zrow::tiled::Tiled<N, 240, 16, PP, PE>;

/// The number formats presets are drawn in: calls `$then! { [ARGS] VARIANT => TYPE, ... }`
/// with `$then`'s own arguments, then each `zrow::presets::Format` variant the bench draws and
/// its number type. Presets in a format not listed are skipped (a `#` line on the bench, nothing
/// on the host).
macro_rules! preset_formats {
    ($then:ident, $($args:tt)*) => {
        $then! {
            [$($args)*]
            Q16_16 => Q16_16,
            F32 => f32,
            // Q24_8: enable when zrow::Q24_8 lands (with `impl zrow_scenes::Format for Q24_8`).
            // Q24_8 => zrow::Q24_8,
        }
    };
}

/// Expands to `$run!(TYPE)` with the number type of `$preset`'s format, or to `$skip` if the
/// bench does not draw that format (see `preset_formats!`).
macro_rules! with_preset_format {
    ($preset:expr, $run:ident, $skip:expr) => {
        preset_formats!(dispatch_preset_format, $preset, $run, $skip)
    };
}

/// `with_preset_format!`'s match, from `preset_formats!`' list.
macro_rules! dispatch_preset_format {
    ([$preset:expr, $run:ident, $skip:expr] $($variant:ident => $t:ty),* $(,)?) => {{
        // The catch-all arm is unreachable once every format is listed.
        #[allow(unreachable_patterns)]
        let done = match $preset.format {
            $(zrow::presets::Format::$variant => $run!($t),)*
            _ => $skip,
        };
        done
    }};
}
