//! The fastest of repeated runs within a time budget: the machine is shared, and one
//! interruption can double a run of a few milliseconds, so each figure is the quietest run.

use std::time::{Duration, Instant};

/// Each figure is the fastest of the runs that fit in this budget (at least one): a set of
/// camera rays takes a millisecond or two in `f64`, and a single run on a shared machine can
/// take up to twice as long as the next.
pub const TIMING_BUDGET: Duration = Duration::from_millis(100);

/// `f`'s output and the time it took.
pub fn timed<T>(f: impl FnOnce() -> T) -> (T, Duration) {
    let start = Instant::now();
    let out = f();
    (out, start.elapsed())
}

/// The first run's output and the fastest run's time, of runs made until their times add up
/// to `budget` (at least one). Each run gives its output and the time of the part to be timed
/// (see [`timed`]; setting up, such as allocating a frame, is left out). `None` as soon as a
/// run gives none (cancelled).
pub fn fastest_cancellable<T>(
    budget: Duration,
    mut run: impl FnMut() -> Option<(T, Duration)>,
) -> Option<Fastest<T>> {
    let (out, mut fastest) = run()?;
    let mut spent = fastest;
    while spent < budget {
        // (The output is the same every run.)
        let (_, time) = run()?;
        (fastest, spent) = (fastest.min(time), spent + time);
    }
    Some(Fastest { out, fastest })
}

/// [`fastest_cancellable`] for runs that cannot be cancelled.
pub fn fastest<T>(budget: Duration, mut run: impl FnMut() -> (T, Duration)) -> Fastest<T> {
    match fastest_cancellable(budget, || Some(run())) {
        Some(fastest) => fastest,
        None => unreachable!("every run gives an output"),
    }
}

/// What [`fastest_cancellable`] measured.
#[derive(Debug, PartialEq)]
pub struct Fastest<T> {
    /// The first run's output.
    pub out: T,
    /// The time of the fastest run.
    pub fastest: Duration,
}

#[cfg(test)]
mod tests {
    use super::*;

    const BUDGET: Duration = Duration::from_millis(100);

    /// The first run's output comes back with the fastest run's time: here a first run that
    /// sleeps 30 ms and runs after it that do nothing.
    #[test]
    fn the_fastest_run_is_timed_and_the_first_output_kept() {
        let mut runs = 0;
        let measured = fastest(BUDGET, || {
            runs += 1;
            timed(|| {
                if runs == 1 {
                    std::thread::sleep(Duration::from_millis(30));
                }
                runs
            })
        });
        assert_eq!(measured.out, 1);
        assert!(runs > 1, "{runs} runs");
        assert!(measured.fastest < Duration::from_millis(30), "{measured:?}");
    }

    /// Runs are made until their reported times add up to the budget, and the fastest is the
    /// one that reported least: here runs of 10 ms but for one of 5 ms.
    #[test]
    fn runs_are_made_until_their_times_fill_the_budget() {
        let mut runs = 0u64;
        let measured = fastest(BUDGET, || {
            runs += 1;
            (runs, Duration::from_millis(if runs == 4 { 5 } else { 10 }))
        });
        // Ten runs add up to 9 x 10 ms + 5 ms = 95 ms, so an eleventh fills the budget.
        assert_eq!(runs, 11);
        assert_eq!(measured.fastest, Duration::from_millis(5));
        assert_eq!(measured.out, 1);
    }

    /// A run that gives nothing (a render cancelled) ends the measurement with nothing.
    #[test]
    fn a_cancelled_run_gives_no_measurement() {
        let mut runs = 0;
        let measured = fastest_cancellable(BUDGET, || {
            runs += 1;
            (runs < 3).then_some((runs, Duration::ZERO))
        });
        assert_eq!(measured, None);
        assert_eq!(runs, 3);
    }
}
