//! Sizes solver calls to the frame's deadline. Every long task (relaxation,
//! growth, the solver race, a parameter study) works in calls of some
//! number of sweeps; the pacer picks that number so that one call takes
//! about a quarter of the budget left, and says whether another call fits.

use web_time::{Duration, Instant};

/// Most sweeps one call is given.
const MAX_SWEEPS_PER_CALL: usize = 10_000;

/// Most a call grows over the last one.
const GROWTH: usize = 4;

/// Share of the frame's remaining budget one call is sized to.
const SHARE_OF_WHAT_IS_LEFT: f64 = 0.25;

/// Sweeps per call: adapted to the deadline, or fixed by the user.
#[derive(Clone, Debug)]
pub struct Pacer {
    per_call: usize,
    fixed: Option<usize>,
    /// The longest call since the last [`restart`](Self::restart).
    longest: Duration,
    /// A call that would overrun its deadline (if it took as long as the
    /// longest) is left to work done elsewhere ([`may_start`](Self::may_start)).
    leave_long: bool,
}

impl Default for Pacer {
    fn default() -> Self {
        Self {
            per_call: 1,
            fixed: None,
            longest: Duration::ZERO,
            leave_long: false,
        }
    }
}

impl Pacer {
    /// Sweeps for the next call.
    pub fn sweeps(&self) -> usize {
        self.fixed.unwrap_or(self.per_call).max(1)
    }

    /// `Some(n)`: one call of `n` sweeps per frame (to watch a relaxation
    /// slowly); `None`: as many as the frame allows.
    pub fn set_fixed(&mut self, sweeps: Option<usize>) {
        self.fixed = sweeps;
    }

    /// The fixed sweeps per frame, if set.
    pub fn fixed(&self) -> Option<usize> {
        self.fixed
    }

    /// In a browser's frames while the job also works between frames
    /// (`web_work`): no call starts in a frame that would overrun it if it
    /// took as long as the longest so far; the work between frames does
    /// it. A frame of the app then holds its UI and the calls that surely
    /// fit: single growth calls reach 20 ms in WebAssembly, and with the
    /// last call as the guess instead of the longest, the app's CPU per
    /// frame had a p95 of 22.6 ms on the default scene's run, not 7.8.
    pub fn set_leave_long(&mut self, on: bool) {
        self.leave_long = on;
    }

    /// Whether a call may start before `deadline` (see
    /// [`set_leave_long`](Self::set_leave_long)).
    pub fn may_start(&self, deadline: Instant) -> bool {
        !self.leave_long || self.fixed.is_some() || Instant::now() + self.longest < deadline
    }

    /// Back to one sweep per call: the cost of a sweep on a new
    /// simulation is unknown.
    pub fn restart(&mut self) {
        self.per_call = 1;
        self.longest = Duration::ZERO;
    }

    /// A call that cannot be split and may take as long as the longest one
    /// so far (a numeric factorisation) comes next: whether to leave it to
    /// the next frame, because it would overrun this one. If so, that call
    /// is one sweep, so that the frame holds the factorisation and little
    /// else.
    pub fn defer_long_call(&mut self, deadline: Instant) -> bool {
        let defer = self.fixed.is_none() && Instant::now() + self.longest >= deadline;
        if defer {
            self.per_call = 1;
        }
        defer
    }

    /// After a call of `sweeps` sweeps that started at `start`: whether
    /// another call fits before `deadline`. No call is started that would
    /// overrun the frame if it took as long as this one (setup calls, e.g.
    /// a factorisation, come in runs); when another fits, the next is sized
    /// to about a quarter of the budget left, and after an overrun it is
    /// halved. A call of no sweeps (a setup, a build) changes only whether
    /// another fits. With fixed sweeps, one call per frame.
    pub fn another_fits(&mut self, start: Instant, sweeps: usize, deadline: Instant) -> bool {
        if self.fixed.is_some() {
            return false;
        }
        let now = Instant::now();
        let took = now - start;
        self.longest = self.longest.max(took);
        let fits = now + took < deadline;
        if sweeps > 0 {
            if now >= deadline {
                self.per_call = (sweeps / 2).max(1);
            } else if fits {
                // at most four times the last call: a call that took next
                // to nothing (a relaxation's setup, a timer's resolution)
                // sized the next to 10 000 sweeps, 9 s on a 120 × 120
                // automaton plate, and its window stayed blank that long
                self.per_call = sized(took, sweeps, deadline - now).min(GROWTH * sweeps);
            }
        }
        fits
    }
}

/// Sweeps of a call taking [`SHARE_OF_WHAT_IS_LEFT`] of `left`, when
/// `sweeps` sweeps took `took`.
fn sized(took: Duration, sweeps: usize, left: Duration) -> usize {
    let per_sweep = took.as_secs_f64() / sweeps.max(1) as f64;
    ((SHARE_OF_WHAT_IS_LEFT * left.as_secs_f64() / per_sweep.max(1e-7)) as usize)
        .clamp(1, MAX_SWEEPS_PER_CALL)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 10 sweeps took 1 ms and 8 ms are left: a quarter of that, 2 ms, is
    /// 20 sweeps; the count stays within [1, 10 000].
    #[test]
    fn a_call_is_sized_to_a_quarter_of_what_is_left() {
        let ms = Duration::from_millis;
        assert_eq!(sized(ms(1), 10, ms(8)), 20);
        assert_eq!(sized(ms(100), 1, ms(1)), 1);
        assert_eq!(sized(Duration::ZERO, 1, ms(8)), MAX_SWEEPS_PER_CALL);
    }

    /// A call that took no measurable time gives the next at most four
    /// times its sweeps, not the most a call can have.
    #[test]
    fn a_call_that_took_no_time_grows_the_next_fourfold_at_most() {
        let mut p = Pacer::default();
        let far = Instant::now() + Duration::from_secs(1);
        assert!(p.another_fits(Instant::now(), 1, far));
        assert!(p.sweeps() <= 4, "{}", p.sweeps());
        let n = p.sweeps();
        assert!(p.another_fits(Instant::now(), n, far));
        assert!(p.sweeps() <= 4 * n, "{}", p.sweeps());
    }

    /// With long calls left to the work between frames, a call as long as
    /// the longest so far starts only if it fits before the deadline;
    /// without, or with a fixed pace, every call may start.
    #[test]
    fn a_long_call_waits_for_the_work_between_frames() {
        let ms = Duration::from_millis;
        let mut p = Pacer::default();
        let start = Instant::now()
            .checked_sub(ms(20))
            .expect("a clock past 20 ms");
        let _ = p.another_fits(start, 1, Instant::now());
        let soon = Instant::now() + ms(5);
        assert!(p.may_start(soon), "long calls are not left by default");
        p.set_leave_long(true);
        assert!(!p.may_start(soon), "a 20 ms call does not fit in 5 ms");
        assert!(p.may_start(Instant::now() + ms(60_000)));
        p.set_fixed(Some(3));
        assert!(p.may_start(soon), "a fixed pace makes one call a frame");
    }

    #[test]
    fn an_overrun_halves_the_call_and_a_fixed_pace_is_one_call() {
        let mut p = Pacer::default();
        let start = Instant::now();
        assert!(!p.another_fits(start, 64, start));
        assert_eq!(p.sweeps(), 32);
        p.set_fixed(Some(7));
        assert_eq!(p.sweeps(), 7);
        let later = Instant::now() + Duration::from_secs(1);
        assert!(!p.another_fits(Instant::now(), 7, later));
        p.set_fixed(None);
        p.restart();
        assert_eq!(p.sweeps(), 1);
    }

    /// After a call of 20 ms (started 20 ms ago), a long call is left to
    /// the next frame when 10 ms are left (and comes as one sweep), not
    /// when 1 s is; after a restart (a new simulation) nothing is known to
    /// be long.
    #[test]
    fn a_long_call_is_left_to_the_next_frame_when_it_would_overrun() {
        let ms = Duration::from_millis;
        let mut p = Pacer::default();
        let far = Instant::now() + ms(1000);
        let start = Instant::now()
            .checked_sub(ms(20))
            .expect("20 ms after boot");
        assert!(p.another_fits(start, 64, far));
        let sized = p.sweeps();
        assert!(sized > 1, "sized to what is left: {sized}");
        assert!(!p.defer_long_call(far));
        assert_eq!(p.sweeps(), sized);
        assert!(p.defer_long_call(Instant::now() + ms(10)));
        assert_eq!(p.sweeps(), 1);
        p.restart();
        assert!(!p.defer_long_call(Instant::now() + ms(10)));
    }
}
