//! Moving around the diagram: the cursor (a value of the swept parameter and a height),
//! setting the swept parameter to the cursor, zooming (about the cursor, to a window
//! or box marked with two corners, vertically by marking two heights in one column),
//! and the zoom stack.

use super::Diagram;
use crate::tui::components::Shared;
use crate::tui::keymap::Action;
use crate::tui::params::ParamId;

/// A window to go back to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Zoom {
    pub lo: f64,
    pub hi: f64,
    pub y: Option<(f64, f64)>,
}

impl Diagram {
    pub(super) fn move_cursor(&mut self, dir: i32, fine: bool, shared: &Shared) {
        let (lo, hi) = (shared.params.lo, shared.params.hi);
        let cols = (self.grid.sub_size().0).max(1) as f64;
        let step = if fine {
            (hi - lo) / cols
        } else {
            (hi - lo) / 20.0
        };
        self.cursor = (self.cursor + dir as f64 * step).clamp(lo, hi);
    }

    /// Move the height cursor by one character row.
    pub(super) fn move_ycursor(&mut self, dir: i32) {
        let y = self.grid.y_range();
        let rows = self.grid.size().1.max(1) as f64;
        self.ycursor = (self.ycursor + dir as f64 * y.span() / rows).clamp(y.lo, y.hi);
    }

    /// Set the swept parameter (α, r or a family's) to the cursor.
    pub fn set_value_to_cursor(&mut self, shared: &mut Shared) {
        let Some(id) = shared.params.row_of(shared.params.param) else {
            return;
        };
        let before = shared.params.clone();
        let r = shared.params.set_text(id, &format!("{}", self.cursor));
        shared.after_change(id, r, &before);
    }

    /// Mark a corner at the cursor; the second corner zooms: to the window between the
    /// two values, and to the heights between them too when they differ by more than a
    /// row (a box); two corners in one column zoom vertically only.
    pub(super) fn mark_corner(&mut self, shared: &mut Shared) {
        let Some((mx, my)) = self.mark.take() else {
            self.mark = Some((self.cursor, self.ycursor));
            let k = |a| shared.keymap.hint(a);
            shared.say(
                format!(
                    "zoom: first corner marked; move the cursor to the other corner and press {} again ({} cancels)",
                    k(Action::MarkWindow),
                    k(Action::Cancel)
                ),
                false,
            );
            return;
        };
        let y = self.grid.y_range();
        let row = y.span() / self.grid.size().1.max(1) as f64;
        let col = (shared.params.hi - shared.params.lo) / self.grid.size().0.max(1) as f64;
        let tall = (my - self.ycursor).abs() > row;
        let wide = (mx - self.cursor).abs() > col;
        let y_box = tall.then(|| (my.min(self.ycursor), my.max(self.ycursor)));
        match (wide, tall) {
            (true, _) => {
                let (lo, hi) = (mx.min(self.cursor), mx.max(self.cursor));
                self.zoom_to(lo, hi, shared);
                if y_box.is_some() {
                    self.y_view = y_box;
                    self.rebin(shared);
                }
            }
            (false, true) => {
                self.push_zoom(shared);
                self.y_view = y_box;
                self.rebin(shared);
                shared.say("zoomed vertically; z goes back", false);
            }
            (false, false) => shared.say(
                "zoom: the two corners are the same point; mark two different values or heights",
                true,
            ),
        }
    }

    fn push_zoom(&mut self, shared: &Shared) {
        self.zoom_stack.push(Zoom {
            lo: shared.params.lo,
            hi: shared.params.hi,
            y: self.y_view,
        });
    }

    /// Zoom to [lo, hi] (clamped to the swept parameter's range), pushing the current
    /// window.
    pub fn zoom_to(&mut self, lo: f64, hi: f64, shared: &mut Shared) {
        let (min, max) = shared.params.window_bounds();
        let lo = lo.max(min);
        let hi = hi.min(max);
        if hi - lo <= 1e-9 || hi.is_nan() || lo.is_nan() {
            shared.say("zoom: the window is empty; mark two different values", true);
            return;
        }
        self.push_zoom(shared);
        self.set_window(lo, hi, shared);
    }

    /// Back to the previous window.
    pub(super) fn zoom_back(&mut self, shared: &mut Shared) {
        match self.zoom_stack.pop() {
            Some(z) => {
                let x_changed = (z.lo, z.hi) != (shared.params.lo, shared.params.hi);
                self.y_view = z.y;
                if x_changed {
                    self.set_window(z.lo, z.hi, shared);
                } else {
                    self.rebin(shared);
                }
            }
            None => shared.say("zoom: already at the first window", true),
        }
    }

    fn set_window(&mut self, lo: f64, hi: f64, shared: &mut Shared) {
        let before = shared.params.clone();
        shared.params.lo = lo;
        shared.params.hi = hi;
        shared.after_change(ParamId::Lo, Ok(()), &before);
    }
}
