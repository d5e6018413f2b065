//! The simulator window (feature `window`, needs SDL2: `apt-get install libsdl2-dev`).
//!
//! `zrow-sim [--paused]` shows [`crate::demo`] at 240×240, scaled 2×. Keys: `m` next
//! method, `f` Q16.16 ↔ f32, space pause, `s` or Right one step (pauses), `n` next scene, `c`
//! back-face culling on/off, Escape or `q` quit.
//!
//! SDL is asked first whether it can open a display ([`NoWindow`] if not), because the
//! simulator panics when it cannot.

use crate::demo::{self, Action, DemoArgs, Renderers, View, SCALE, TITLE};
use crate::model::LoadedModel;
use embedded_graphics_simulator::sdl2::Keycode;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorEvent, Window};
use std::time::Duration;

/// Why no window could be opened (one line).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NoWindow(pub String);

/// The action of a key, if it has one.
pub fn action(key: Keycode) -> Option<Action> {
    Some(match key {
        Keycode::M => Action::NextMethod,
        Keycode::F => Action::ToggleFormat,
        Keycode::SPACE => Action::TogglePause,
        Keycode::S | Keycode::RIGHT => Action::Step,
        Keycode::N => Action::NextScene,
        Keycode::C => Action::ToggleCull,
        Keycode::Q | Keycode::ESCAPE => Action::Quit,
        _ => return None,
    })
}

/// Asks SDL for its video subsystem; the context is kept while the window is open.
fn probe() -> Result<sdl2::Sdl, NoWindow> {
    if std::env::var_os("DISPLAY").is_none() && std::env::var_os("WAYLAND_DISPLAY").is_none() {
        return Err(NoWindow("DISPLAY is not set".into()));
    }
    let sdl = sdl2::init().map_err(|e| NoWindow(format!("SDL cannot start: {e}")))?;
    sdl.video()
        .map_err(|e| NoWindow(format!("SDL cannot open the display: {e}")))?;
    Ok(sdl)
}

/// Opens the window and runs the demo until it is closed (or `--frames` updates have passed).
pub fn run(args: &DemoArgs, model: Option<&LoadedModel>) -> Result<(), NoWindow> {
    let _sdl = probe()?;
    let settings = OutputSettingsBuilder::new().scale(SCALE).build();
    let mut window = Window::new(TITLE, &settings);
    let mut display = demo::new_display();
    let mut renderers = Renderers::new();
    let mut view = View {
        paused: args.paused,
        has_model: model.is_some(),
        ..View::default()
    };
    let mut dirty = true;
    let mut average: Option<Duration> = None;
    let mut updates = 0u64;
    loop {
        if dirty || !view.paused {
            let frame = demo::render(&mut renderers, &view, model, &mut display);
            // A running average over about 16 frames, so the figure can be read.
            let shown = match average {
                Some(a) if frame.result.is_ok() => (a * 15 + frame.time) / 16,
                _ => frame.time,
            };
            average = Some(shown);
            demo::draw_status(&mut display, &view, &frame, shown);
            if !view.paused {
                view.advance();
            }
            dirty = false;
        }
        window.update(&display);
        for event in window.events() {
            match event {
                SimulatorEvent::Quit => return Ok(()),
                SimulatorEvent::KeyDown { keycode, .. } => match action(keycode) {
                    Some(Action::Quit) => return Ok(()),
                    Some(a) => {
                        let before = view;
                        view.apply(a);
                        if before.format != view.format || before.scene != view.scene {
                            average = None;
                        }
                        dirty = true;
                    }
                    None => {}
                },
                _ => {}
            }
        }
        updates += 1;
        if args.frames.is_some_and(|n| updates >= n) {
            return Ok(());
        }
    }
}
