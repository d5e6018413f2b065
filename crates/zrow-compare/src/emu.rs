//! The emulated Cortex-M4's instruction counts, read from `emu/run.sh m4`'s output file.
//!
//! Lines look like `method=NAME scene=NAME format=FMT tris=N instructions=N ram=BYTES
//! hash=HEX`; lines starting with `#` are the bench's notes (its target, the calibration pairs).

use std::collections::BTreeMap;
use std::path::Path;

/// One emulated frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Guest instructions from the start marker to the stop marker (not cycles).
    pub instructions: u64,
    /// The line's `ram=` field (see emu/README.md for what it means per method).
    pub ram: u64,
}

/// The frames of one run, by (method, scene), Q16.16 only, and the bench's notes.
#[derive(Clone, Debug, Default)]
pub struct Counts {
    /// Frames by `(method, scene)`.
    pub frames: BTreeMap<(String, String), Frame>,
    /// The `#` lines (bench header, calibration).
    pub notes: Vec<String>,
}

impl Counts {
    /// The count for `method` on `scene`.
    pub fn get(&self, method: &str, scene: &str) -> Option<Frame> {
        self.frames
            .get(&(method.to_string(), scene.to_string()))
            .copied()
    }
}

/// Parses the bench output; lines without `method=` are the scan-line's (the bench's older
/// format).
pub fn parse(text: &str) -> Counts {
    let mut counts = Counts::default();
    for line in text.lines() {
        if line.starts_with('#') {
            counts.notes.push(line.to_string());
            continue;
        }
        let field = |key: &str| {
            line.split_whitespace()
                .find_map(|kv| kv.strip_prefix(key)?.strip_prefix('='))
        };
        let (Some(scene), Some(format), Some(instr)) =
            (field("scene"), field("format"), field("instructions"))
        else {
            continue;
        };
        let (Ok(instructions), true) = (instr.parse(), format == "q16.16") else {
            continue;
        };
        let method = field("method").unwrap_or("scanline");
        let ram = field("ram").and_then(|r| r.parse().ok()).unwrap_or(0);
        counts.frames.insert(
            (method.to_string(), scene.to_string()),
            Frame { instructions, ram },
        );
    }
    counts
}

/// Reads and parses `path`; the error says how to make the file.
pub fn read(path: &Path) -> Result<Counts, String> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        format!(
            "{}: {e}; make it with `bash emu/run.sh m4` (QEMU, about a minute), then run this again",
            path.display()
        )
    })?;
    let counts = parse(&text);
    if counts.frames.is_empty() {
        return Err(format!(
            "{}: no frame lines; rerun `bash emu/run.sh m4`",
            path.display()
        ));
    }
    Ok(counts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_method_lines_and_old_scanline_lines() {
        let text = "# zrow emulated bench, target thumbv7em-none-eabihf\n\
            scene=cube format=q16.16 tris=6 instructions=1083467 ram=2058 hash=0f4dfaed4b499447\n\
            method=depth-sort scene=foley100 format=q16.16 tris=100 instructions=42 ram=7 hash=00\n\
            method=bsp scene=foley100 format=f32 tris=100 instructions=9 ram=7 hash=00\n\
            method=bsp scene=foley100 format=q16.16 tris=100 instructions=? ram=7 hash=00\n";
        let c = parse(text);
        assert_eq!(c.notes.len(), 1);
        assert_eq!(
            c.get("scanline", "cube"),
            Some(Frame {
                instructions: 1_083_467,
                ram: 2058
            })
        );
        assert_eq!(
            c.get("depth-sort", "foley100").map(|f| f.instructions),
            Some(42)
        );
        // f32 lines and unfilled counts are skipped.
        assert_eq!(c.get("bsp", "foley100"), None);
        assert_eq!(c.frames.len(), 2);
    }

    #[test]
    fn a_missing_file_says_how_to_make_it() {
        let e = read(Path::new("/nonexistent/bench-m4.txt")).unwrap_err();
        assert!(e.contains("bash emu/run.sh m4"), "{e}");
    }
}
