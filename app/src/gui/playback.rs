//! Playback, as in a viewer: play and pause (the button, or the space
//! bar), speed 0.25x-4x, loop, and the clock: each motion at its own real
//! duration (the selected demo over its duration, a new target's run over
//! its T), or all in unit time (one unit a second at 1x). Time advances by
//! each frame's real time, so the speed does not depend on the frame rate;
//! a frame does no work but moving the cursors on paths already computed.

use eframe::egui;

/// The speeds offered.
pub const SPEEDS: [f64; 5] = [0.25, 0.5, 1.0, 2.0, 4.0];

/// The playback's state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Playback {
    /// Whether it plays.
    pub playing: bool,
    /// How many times real time.
    pub speed: f64,
    /// Whether it starts again at the end.
    pub looping: bool,
    /// Real time (each motion at its own duration) or unit time.
    pub real_time: bool,
    /// The clock: seconds in real time, unit times in unit time.
    pub clock: f64,
}

impl Default for Playback {
    fn default() -> Self {
        Self {
            playing: false,
            speed: 1.0,
            looping: true,
            real_time: true,
            clock: 0.0,
        }
    }
}

/// The durations the cursors follow, seconds: the selected demo's, and a
/// new target's run's where there is one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Durations {
    /// The selected demo's duration.
    pub demo: f64,
    /// The new target's run's duration T.
    pub target: Option<f64>,
}

impl Playback {
    /// Where the clock ends: the longest motion in real time, 1 in unit
    /// time.
    pub fn end(&self, d: Durations) -> f64 {
        if self.real_time {
            d.demo.max(d.target.unwrap_or(0.0)).max(1e-6)
        } else {
            1.0
        }
    }

    /// Advances the clock by a frame of `dt` seconds; at the end it starts
    /// again (looping) or stops there.
    pub fn advance(&mut self, dt: f64, d: Durations) {
        if !(self.playing && dt.is_finite() && dt > 0.0) {
            return;
        }
        let end = self.end(d);
        self.clock += dt * self.speed;
        if self.clock >= end {
            if self.looping {
                self.clock %= end;
            } else {
                self.clock = end;
                self.playing = false;
            }
        }
    }

    /// The selected demo's cursor, unit time.
    pub fn demo_t(&self, d: Durations) -> f64 {
        self.unit(d.demo)
    }

    /// The new target's run's cursor, unit time.
    pub fn target_t(&self, d: Durations) -> f64 {
        self.unit(d.target.unwrap_or(d.demo))
    }

    fn unit(&self, duration: f64) -> f64 {
        let t = if self.real_time {
            self.clock / duration.max(1e-9)
        } else {
            self.clock
        };
        t.clamp(0.0, 1.0)
    }

    /// Sets the clock where a cursor was put by hand (`t` of the selected
    /// demo, unit time).
    pub fn seek(&mut self, t: f64, d: Durations) {
        self.clock = if self.real_time { t * d.demo } else { t };
    }

    /// Starts or pauses; at the end of a run that stopped, starts again.
    pub fn toggle(&mut self, d: Durations) {
        self.playing = !self.playing;
        if self.playing && self.clock >= self.end(d) {
            self.clock = 0.0;
        }
    }
}

/// The controls: play or pause, the speed, loop and the clock.
pub fn controls_ui(ui: &mut egui::Ui, p: &mut Playback, d: Durations) {
    // ASCII: a glyph egui's fonts lack (or one with an emoji presentation)
    // is drawn in the browser through a Canvas 2D fallback, 20-50 ms the first
    // time, in the frame that starts the landscape (web/tests/slow_frame.mjs).
    let label = if p.playing { "Pause" } else { "Play" };
    if ui
        .button(label)
        .on_hover_text("play the motion as recorded (space bar)")
        .clicked()
    {
        p.toggle(d);
    }
    egui::ComboBox::from_label("speed")
        .selected_text(format!("{}x", p.speed))
        .width(60.0)
        .show_ui(ui, |ui| {
            for s in SPEEDS {
                ui.selectable_value(&mut p.speed, s, format!("{s}x"));
            }
        });
    ui.checkbox(&mut p.looping, "loop");
    let before = p.real_time;
    egui::ComboBox::from_label("clock")
        .selected_text(if p.real_time {
            "real time"
        } else {
            "unit time"
        })
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut p.real_time, true, "real time")
                .on_hover_text("each motion at its own duration (the demo's, a new target's T)");
            ui.selectable_value(&mut p.real_time, false, "unit time")
                .on_hover_text("every motion over one unit of time (a second at 1x)");
        });
    if p.real_time != before {
        // The cursor stays where it is.
        let t = if before {
            p.clock / d.demo.max(1e-9)
        } else {
            p.clock
        };
        p.seek(t.clamp(0.0, 1.0), d);
    }
}
