//! What accuracy costs, for the view on screen (the viewer's accuracy panel): measuring every
//! arithmetic's time per ray and pixels differing from exact, and comparing the frame on screen
//! with its exact render. Both run on background threads of their own and start only once the
//! view has converged; a change of view cancels them. A measurement then starts again by itself
//! for the new view (it was asked for and never finished); a finished table stays, marked as
//! being of an earlier view. The comparison, while switched on, follows the view: it is redone
//! for every converged frame, and its overlay shows only on the frame it was made for.

mod compare;
mod measure;
pub mod panel;
mod plot;

pub use compare::Comparison;
pub use measure::{ns_per_ray, Measurement, Subject};

use super::background::{Background, Report};
use super::worker::RenderedFrame;
use compare::CompareJob;
use measure::MeasureJob;
use std::sync::Arc;

/// Where the measurement is.
#[derive(Clone, Default)]
pub enum MeasureState {
    #[default]
    Idle,
    /// Asked for; starts when the view has converged.
    Waiting,
    Running {
        generation: u64,
        subject: Subject,
        report: Option<Arc<Report<Measurement>>>,
    },
    Done {
        subject: Subject,
        measurement: Arc<Measurement>,
    },
    /// Cancelled by a second click, with the rows measured until then.
    Cancelled {
        partial: Option<Arc<Measurement>>,
    },
    Failed(String),
}

impl MeasureState {
    /// A short name for the state report.
    pub fn label(&self) -> &'static str {
        match self {
            MeasureState::Idle => "idle",
            MeasureState::Waiting => "waiting",
            MeasureState::Running { .. } => "running",
            MeasureState::Done { .. } => "done",
            MeasureState::Cancelled { .. } => "cancelled",
            MeasureState::Failed(_) => "failed",
        }
    }

    /// The rows to show: finished, partial or cancelled.
    pub fn measurement(&self) -> Option<&Measurement> {
        match self {
            MeasureState::Running { report, .. } => report.as_ref()?.result.as_ref(),
            MeasureState::Done { measurement, .. } => Some(measurement),
            MeasureState::Cancelled { partial } => partial.as_deref(),
            _ => None,
        }
    }
}

/// Where the comparison with exact is.
#[derive(Clone, Default)]
pub enum CompareState {
    #[default]
    Off,
    /// Switched on; starts when the view has converged.
    Waiting,
    Running {
        generation: u64,
        frame: u64,
        report: Option<Arc<Report<Arc<Comparison>>>>,
    },
    Done(Arc<Comparison>),
}

impl CompareState {
    /// A short name for the state report.
    pub fn label(&self) -> &'static str {
        match self {
            CompareState::Off => "off",
            CompareState::Waiting => "waiting",
            CompareState::Running { .. } => "running",
            CompareState::Done(_) => "done",
        }
    }
}

/// The measurement and comparison as the panel shows and edits them.
pub struct AccuracyState {
    /// Pixels of the measured frame (one of [`measure::PIXEL_BUDGETS`]).
    pub budget: u32,
    pub measure: MeasureState,
    pub compare_on: bool,
    pub compare: CompareState,
    /// What the frame on screen shows, as far as a measurement depends on it (to tell a
    /// result of an earlier view).
    pub subject: Option<Subject>,
    /// The generation of the frame on screen (the overlay belongs to one frame).
    pub shown_generation: Option<u64>,
}

impl Default for AccuracyState {
    fn default() -> Self {
        AccuracyState {
            budget: measure::PIXEL_BUDGETS[0],
            measure: MeasureState::Idle,
            compare_on: false,
            compare: CompareState::Off,
            subject: None,
            shown_generation: None,
        }
    }
}

impl AccuracyState {
    /// Whether the finished measurement is of another view than the one on screen.
    pub fn measured_elsewhere(&self) -> bool {
        matches!(&self.measure, MeasureState::Done { subject, .. }
            if self.subject.as_ref().is_some_and(|s| s != subject))
    }

    /// The comparison of the frame on screen, if done.
    pub fn comparison_shown(&self) -> Option<&Comparison> {
        match &self.compare {
            CompareState::Done(c)
                if self.compare_on && Some(c.generation) == self.shown_generation =>
            {
                Some(c)
            }
            _ => None,
        }
    }
}

/// The two background threads and what starts, cancels and collects their work.
pub struct Accuracy {
    measurer: Background<MeasureJob, Measurement>,
    comparer: Background<CompareJob, Arc<Comparison>>,
}

impl Accuracy {
    /// Starts the threads; `notify` wakes the window when either reports.
    pub fn start(notify: impl Fn() + Clone + Send + Sync + 'static) -> std::io::Result<Accuracy> {
        // One thread: times per ray like `bench accuracy`'s, and a core left for the view.
        let measurer = Background::start("heightray-measure", 1, measure::run, notify.clone())?;
        let threads = std::thread::available_parallelism().map_or(1, usize::from);
        let comparer = Background::start("heightray-compare", threads, compare::run, notify)?;
        Ok(Accuracy { measurer, comparer })
    }

    /// The measure button: starts a measurement, or cancels the one under way.
    pub fn toggle_measure(&self, state: &mut AccuracyState) {
        state.measure = match &state.measure {
            MeasureState::Running { report, .. } => {
                self.measurer.cancel();
                let partial = report.as_ref().and_then(|r| r.result.clone());
                MeasureState::Cancelled {
                    partial: partial.map(Arc::new),
                }
            }
            MeasureState::Waiting => MeasureState::Idle,
            _ => MeasureState::Waiting,
        };
    }

    /// Called on every redraw: `converged` is the frame on screen if it is complete and shows
    /// the current view at full resolution; `shown` is the frame on screen.
    pub fn update(
        &self,
        state: &mut AccuracyState,
        converged: Option<&Arc<RenderedFrame>>,
        shown: Option<&Arc<RenderedFrame>>,
    ) {
        state.subject = shown.map(|frame| Subject::of(&frame.job));
        state.shown_generation = shown.map(|frame| frame.generation);
        self.update_measure(state, converged);
        self.update_compare(state, converged);
    }

    fn update_measure(&self, state: &mut AccuracyState, converged: Option<&Arc<RenderedFrame>>) {
        let next = match &state.measure {
            MeasureState::Waiting => converged.map(|frame| MeasureState::Running {
                generation: self
                    .measurer
                    .submit(MeasureJob::new(Arc::clone(frame), state.budget)),
                subject: Subject::of(&frame.job),
                report: None,
            }),
            // What it measures changed under it: start again once the new view has converged.
            // Another arithmetic on screen is no change: every one is measured.
            MeasureState::Running { subject, .. }
                if state.subject.as_ref().is_some_and(|s| s != subject) =>
            {
                self.measurer.cancel();
                Some(MeasureState::Waiting)
            }
            MeasureState::Running {
                generation,
                subject,
                ..
            } => self.measurer.report(*generation).map(|report| {
                match (&report.result, report.finished) {
                    (Some(m), true) => MeasureState::Done {
                        subject: subject.clone(),
                        measurement: Arc::new(m.clone()),
                    },
                    (None, true) => MeasureState::Failed(report.status.clone()),
                    _ => MeasureState::Running {
                        generation: *generation,
                        subject: subject.clone(),
                        report: Some(report),
                    },
                }
            }),
            _ => None,
        };
        if let Some(next) = next {
            state.measure = next;
        }
    }

    fn update_compare(&self, state: &mut AccuracyState, converged: Option<&Arc<RenderedFrame>>) {
        if !state.compare_on {
            if matches!(state.compare, CompareState::Running { .. }) {
                self.comparer.cancel();
            }
            state.compare = CompareState::Off;
            return;
        }
        let current = converged.map(|f| f.generation);
        match &state.compare {
            CompareState::Running { frame, .. } if Some(*frame) != current => {
                self.comparer.cancel();
                state.compare = CompareState::Waiting;
            }
            CompareState::Running {
                generation, frame, ..
            } => {
                let Some(report) = self.comparer.report(*generation) else {
                    return;
                };
                state.compare = match (&report.result, report.finished) {
                    (Some(comparison), true) => CompareState::Done(Arc::clone(comparison)),
                    _ => CompareState::Running {
                        generation: *generation,
                        frame: *frame,
                        report: Some(report),
                    },
                };
            }
            CompareState::Done(c) if Some(c.generation) == current => {}
            // Switched on, or done for an earlier frame: compare the converged one.
            _ => match converged {
                Some(frame) => {
                    let job = CompareJob {
                        frame: Arc::clone(frame),
                    };
                    state.compare = CompareState::Running {
                        generation: self.comparer.submit(job),
                        frame: frame.generation,
                        report: None,
                    };
                }
                None if matches!(state.compare, CompareState::Off) => {
                    state.compare = CompareState::Waiting;
                }
                None => {}
            },
        }
    }
}
