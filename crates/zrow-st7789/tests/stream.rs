//! The whole-frame protocol of a DMA sender, checked against the panel model: the init table,
//! then per frame the window (CASET, RASET), RAMWR and `height` rows of `encode_row` bytes
//! (each row one data write, as one DMA transfer sends it). The firmwares' sink
//! (`zrow_st7789::dma::DmaRows`) sends whole frames like this only at first and after an
//! error; `coherence.rs` checks it, changed rows and all. Two consecutive frames of a turning standard
//! scene must each equal the core's render bit for bit, and the model must see no protocol
//! error.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{FrameBuffer, Row, RowSink, Scanline, Q16_16};
use zrow_st7789::command::{CASET, RAMWR, RASET};
use zrow_st7789::model::St7789Model;
use zrow_st7789::{encode_row, init_sequence, Window};

/// A whole-frame DMA sender: per frame the window, then each row's big-endian bytes, DC high.
struct DmaLike<'a> {
    model: &'a mut St7789Model,
    line: [u8; 480],
}

impl<N> RowSink<N> for DmaLike<'_> {
    type Error = ();
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), ()> {
        if row.y == 0 {
            // Each frame: the window, then RAMWR (the address counter to its corner).
            let window = Window::new(240, 240);
            for (cmd, params) in [
                (CASET, &window.caset()[..]),
                (RASET, &window.raset()),
                (RAMWR, &[]),
            ] {
                self.model.feed(false, &[cmd]);
                self.model.feed(true, params);
            }
        }
        let n = encode_row(row.color, &mut self.line);
        self.model.feed(true, &self.line[..n]);
        Ok(())
    }
}

#[test]
fn window_ramwr_and_rows_each_frame() {
    let mut model = St7789Model::new();
    for &(cmd, params, delay_ms) in init_sequence() {
        model.feed(false, &[cmd]);
        model.feed(true, params);
        model.advance_ns(delay_ms as u64 * 1_000_000);
    }
    let window = Window::new(240, 240);

    let mut renderer = Box::new(Scanline::<Q16_16, 240, 4096, 1024, 512>::new());
    for (frame, name) in ["mesh1k", "mesh1k", "cube"].iter().enumerate() {
        let angle = frame as f32 * 0.4;
        let mut want = vec![Rgb565::BLACK; 240 * 240];
        zrow_scenes::with_scene::<Q16_16, _>(name, angle, |scene, cfg, _| {
            renderer
                .render(scene, cfg, &mut FrameBuffer::new(&mut want, 240))
                .unwrap();
            let mut sink = DmaLike {
                model: &mut model,
                line: [0; 480],
            };
            renderer.render(scene, cfg, &mut sink).unwrap();
        })
        .unwrap();
        assert_eq!(model.read_window(&window), want, "frame {frame} ({name})");
        assert!(want.iter().any(|&p| p != Rgb565::BLACK));
    }
    assert!(model.errors().is_empty(), "{:?}", model.errors());
    assert!(model.display_on() && model.inverted());
}
