//! The windows a run to rest is judged over. They overlap, a new one opening every few
//! steps, so a run stops within a few steps of the end of the first window over which
//! the cloth rested; windows laid end to end stopped it up to a whole window later (the
//! main job's dress rested over steps 14 to 24 of its drape, and went on to step 30).

use super::rest::MIN_WINDOW;
use crate::math::Vec3;
use std::collections::VecDeque;

/// Windows open at once, at most: a window of `n` steps opens a new one every `n / OPEN`
/// steps (rounded up), each holding where every particle was at its start.
const OPEN: usize = 5;

/// One open window: the slot of its start's positions, and the steps and time into it.
#[derive(Debug, Clone, Copy)]
struct Window {
    slot: usize,
    steps: u32,
    time: f64,
}

/// The open windows of a run to rest, oldest first, with the particles' positions at the
/// start of each (allocated by the first run to rest, then reused).
#[derive(Debug, Default)]
pub(super) struct RestWindows {
    starts: Vec<Vec<Vec3>>,
    open: VecDeque<Window>,
    free: Vec<usize>,
    /// Steps of a window, and between the openings of two.
    length: u32,
    stride: u32,
    /// Steps since the newest window opened.
    since_opened: u32,
}

impl RestWindows {
    /// Starts judging windows of `length` steps (and [`MIN_WINDOW`] at least), the first
    /// opening at `x`.
    pub fn start(&mut self, length: u32, x: &[Vec3]) {
        self.length = length;
        self.stride = length.div_ceil(OPEN as u32).max(1);
        self.open.clear();
        self.free.clear();
        self.free.extend((0..self.starts.len()).rev());
        self.open_at(x);
    }

    /// Counts a step of `h` seconds into every open window.
    pub fn advance(&mut self, h: f64) {
        for w in &mut self.open {
            w.steps += 1;
            w.time += h;
        }
        self.since_opened += 1;
    }

    /// The oldest window if it has run its steps and time: its start, and its time.
    pub fn ripe(&self) -> Option<(&[Vec3], f64)> {
        let w = self.open.front()?;
        (w.steps >= self.length && w.time >= MIN_WINDOW).then(|| (&self.starts[w.slot][..], w.time))
    }

    /// Closes the oldest window (judged not at rest).
    pub fn close_oldest(&mut self) {
        if let Some(w) = self.open.pop_front() {
            self.free.push(w.slot);
        }
    }

    /// Opens a window at `x` if none is open or the newest is a stride old, while fewer
    /// than [`OPEN`] are (windows longer than their steps, by [`MIN_WINDOW`], wait).
    pub fn open_if_due(&mut self, x: &[Vec3]) {
        let due = self.open.is_empty() || self.since_opened >= self.stride;
        if due && self.open.len() < OPEN {
            self.open_at(x);
        }
    }

    fn open_at(&mut self, x: &[Vec3]) {
        let slot = self.free.pop().unwrap_or_else(|| {
            self.starts.push(Vec::new());
            self.starts.len() - 1
        });
        let start = &mut self.starts[slot];
        start.clear();
        start.extend_from_slice(x);
        self.open.push_back(Window {
            slot,
            steps: 0,
            time: 0.0,
        });
        self.since_opened = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Steps of `h` at which a window ripens, each judged not at rest, over `steps` steps.
    fn ripening(length: u32, h: f64, steps: u32) -> Vec<(u32, u32)> {
        let mut windows = RestWindows::default();
        let x = [Vec3::zeros()];
        windows.start(length, &x);
        let mut ripe = Vec::new();
        for k in 1..=steps {
            windows.advance(h);
            while let Some((_, time)) = windows.ripe() {
                ripe.push((k, (time / h).round() as u32));
                windows.close_oldest();
            }
            windows.open_if_due(&x);
        }
        ripe
    }

    #[test]
    fn windows_of_ten_steps_are_judged_every_second_step() {
        let ripe = ripening(10, 0.1, 20);
        assert_eq!(ripe, [(10, 10), (12, 10), (14, 10), (16, 10), (18, 10), (20, 10)]);
    }

    #[test]
    fn windows_short_of_the_least_time_wait_for_it_and_stay_few() {
        // Ten steps of 1/64 s are short of the half second: each window runs 32 steps,
        // and five at most are open (from steps 0 to 8), so the next five open as those
        // close, from step 32 to 40, and ripen 32 steps later.
        let h = 1.0 / 64.0;
        let ripe = ripening(10, h, 80);
        let steps: Vec<u32> = ripe.iter().map(|r| r.0).collect();
        assert_eq!(steps, [32, 34, 36, 38, 40, 64, 66, 68, 70, 72]);
        assert!(ripe.iter().all(|r| r.1 == 32), "{ripe:?}");
    }
}
