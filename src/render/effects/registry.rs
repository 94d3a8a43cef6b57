//! What the list of effects makes of each entry (the list is in [`super`]): a field of the
//! frame's counters ([`EffectStats`](super::EffectStats)) and times
//! ([`EffectTime`](super::EffectTime)), reported by the effect's name; for effects asked at
//! each sample, a field of the sample's record ([`Outcomes`](super::Outcomes)) and the call
//! in its stage, before the hit or at it, in the list's order. Everything is made for the
//! types named, so the shader calls each effect directly, inlined: no trait objects on a
//! ray's way.

/// Makes the registry from the list of effects, each entry `name: file::Type` (the file's
/// module is declared here too): `sun` fills the sun's shadow in place of hard shadows (the
/// shader casts it; it is only counted here), `before_hit` and `at_hit` name effects asked at
/// each sample, which the shader calls in that order.
macro_rules! registry {
    (
        sun { $($sun:ident: $sun_file:ident::$sun_ty:ident),* $(,)? }
        before_hit { $($before:ident: $before_file:ident::$before_ty:ident),* $(,)? }
        at_hit { $($at:ident: $at_file:ident::$at_ty:ident),* $(,)? }
    ) => {
        $(mod $sun_file;)*
        $(mod $before_file;)*
        $(mod $at_file;)*
        registry!(
            @counted
            $($sun: $sun_file::$sun_ty,)*
            $($before: $before_file::$before_ty,)*
            $($at: $at_file::$at_ty,)*
        );
        registry!(
            @sampled
            [$($before: $before_file::$before_ty),*]
            [$($at: $at_file::$at_ty),*]
        );
        registry!(
            @stages
            [$($before: $before_file::$before_ty),*]
            [$($at: $at_file::$at_ty),*]
        );
    };

    (@counted $($name:ident: $ty:ty,)*) => {
        /// The effects' counters of a frame: one field per effect of the list, and samples
        /// per pixel.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, derive_more::AddAssign)]
        pub struct EffectStats {
            $(
                #[doc = concat!("What `", stringify!($ty), "` counted.")]
                pub $name: <$ty as Counted>::Stats,
            )*
            /// Samples per pixel.
            pub samples: SampleStats,
        }

        /// Thread time a frame spent, in all and per effect of the list.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, derive_more::AddAssign)]
        pub struct EffectTime {
            /// Tracing and shading the frame's pixels, everything included.
            pub traced: u64,
            $(
                #[doc = concat!("`", stringify!($ty), "`'s part of each sample.")]
                pub $name: u64,
            )*
            /// The samples each pixel took after its first, with their effects' rays.
            pub later_samples: u64,
        }

        /// Where an effect of the list keeps its counters and its time.
        pub trait Listed: Counted {
            /// Its counters among a frame's.
            fn stats(all: &EffectStats) -> &Self::Stats;
            /// Its counters among a frame's, to count into.
            fn stats_mut(all: &mut EffectStats) -> &mut Self::Stats;
            /// Its time among a frame's.
            fn time_mut(all: &mut EffectTime) -> &mut u64;
        }

        $(
            impl Listed for $ty {
                #[inline(always)]
                fn stats(all: &EffectStats) -> &Self::Stats {
                    &all.$name
                }
                #[inline(always)]
                fn stats_mut(all: &mut EffectStats) -> &mut Self::Stats {
                    &mut all.$name
                }
                #[inline(always)]
                fn time_mut(all: &mut EffectTime) -> &mut u64 {
                    &mut all.$name
                }
            }
        )*

        impl EffectStats {
            /// Counts one sample's `outcome` of effect `E`.
            #[inline(always)]
            pub fn count<E: Listed>(&mut self, outcome: &E::Outcome) {
                E::count(outcome, E::stats_mut(self));
            }

            /// Counts one finished pixel that took `samples` camera rays.
            pub fn add_pixel(&mut self, samples: u32) {
                self.samples.add(samples);
            }

            /// The effects as JSON, each under its name; `camera_rays` is the frame's primary
            /// rays (for samples per pixel).
            pub fn to_json(&self, camera_rays: u64) -> serde_json::Value {
                let mut all = serde_json::Map::new();
                $(
                    let counted = serde_json::to_value(&self.$name).unwrap_or_default();
                    all.insert(<$ty as Counted>::NAME.into(), counted);
                )*
                all.insert("samples_per_pixel".into(), self.samples.to_json(camera_rays));
                serde_json::Value::Object(all)
            }

            /// Each effect of the list that counted anything, by its label, with its
            /// counters as `--stats` reports them.
            pub fn counted(&self) -> Vec<(&'static str, serde_json::Value)> {
                let mut counted = Vec::new();
                $(
                    if self.$name != Default::default() {
                        let counters = serde_json::to_value(&self.$name).unwrap_or_default();
                        counted.push((<$ty as Counted>::LABEL, counters));
                    }
                )*
                counted
            }

            /// The rays every effect of the list cast.
            pub fn rays(&self) -> u64 {
                0 $(+ <$ty as Counted>::rays(&self.$name))*
            }

            /// Each effect of the list as a frame counted it, in the list's order; `around`
            /// is the rest of the frame.
            pub fn each(&self, around: &Around<'_>) -> Vec<Summary> {
                vec![$(
                    Summary {
                        name: <$ty as Counted>::NAME,
                        label: <$ty as Counted>::LABEL,
                        word: <$ty as Counted>::WORD,
                        rays: <$ty as Counted>::rays(&self.$name),
                        culled: <$ty as Counted>::culled(&self.$name, around),
                        counters: serde_json::to_value(&self.$name).unwrap_or_default(),
                    },
                )*]
            }
        }

        impl EffectTime {
            /// The share of the traced time each part took (0 to 1): camera rays, hard
            /// shadows and shading (what is left), each effect; and, across those, the
            /// samples after each pixel's first. `None` before anything was timed.
            pub fn shares(&self) -> Option<TimeShares> {
                let effects = [$((<$ty as Counted>::LABEL, self.$name)),*];
                TimeShares::of(self.traced, &effects, self.later_samples)
            }

            /// The times as JSON, in milliseconds of thread time, each effect's under its name.
            pub fn to_json(&self) -> serde_json::Value {
                let ms = |nanos: u64| serde_json::Value::from(nanos as f64 / 1e6);
                let mut all = serde_json::Map::new();
                all.insert("traced".into(), ms(self.traced));
                $(all.insert(<$ty as Counted>::NAME.into(), ms(self.$name));)*
                all.insert("later_samples".into(), ms(self.later_samples));
                serde_json::Value::Object(all)
            }
        }
    };

    (@sampled [$($before:ident: $before_ty:ty),*] [$($at:ident: $at_ty:ty),*]) => {
        /// What each effect of the list asked at each sample did there.
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        pub struct Outcomes {
            $(
                #[doc = concat!("What `", stringify!($before_ty), "` did.")]
                pub $before: <$before_ty as Counted>::Outcome,
            )*
            $(
                #[doc = concat!("What `", stringify!($at_ty), "` did.")]
                pub $at: <$at_ty as Counted>::Outcome,
            )*
        }

        /// Where an effect asked at each sample keeps its outcome in a sample's record.
        pub trait Kept: Listed + Sampled {
            /// Its outcome among a sample's, to record into.
            fn outcome_mut(all: &mut Outcomes) -> &mut Self::Outcome;
        }

        $(
            impl Kept for $before_ty {
                #[inline(always)]
                fn outcome_mut(all: &mut Outcomes) -> &mut Self::Outcome {
                    &mut all.$before
                }
            }
        )*
        $(
            impl Kept for $at_ty {
                #[inline(always)]
                fn outcome_mut(all: &mut Outcomes) -> &mut Self::Outcome {
                    &mut all.$at
                }
            }
        )*

        /// Where each effect's outcome at a sample goes as it is cast: into a frame's
        /// counters, or a sample's record.
        pub trait Record {
            /// Effect `E` showed in place of the terrain, doing `outcome`; its rays asked
            /// `queries`.
            fn before_hit<E: BeforeHit + Kept>(&mut self, outcome: &E::Outcome, queries: &$crate::traverse::Counters);
            /// Effect `E` did `outcome` at the hit.
            fn at_hit<E: AtHit + Kept>(&mut self, outcome: &E::Outcome);
        }

        impl Outcomes {
            /// Passes each effect's outcome, where it was asked, to `record`; `secondary` is
            /// the sample's secondary queries (an effect before the hit asked them).
            pub fn record_into(&self, secondary: &$crate::traverse::Counters, record: &mut impl Record) {
                $(
                    if self.$before != Default::default() {
                        record.before_hit::<$before_ty>(&self.$before, secondary);
                    }
                )*
                $(
                    if self.$at != Default::default() {
                        record.at_hit::<$at_ty>(&self.$at);
                    }
                )*
            }

            /// The queries the effects at the hit asked (those before it asked the
            /// sample's secondary queries).
            pub fn queries_at_hit(&self) -> impl Iterator<Item = $crate::traverse::Counters> {
                [$(<$at_ty as AtHit>::queries(&self.$at)),*].into_iter()
            }
        }
    };

    (@stages [$($before:ident: $before_ty:ty),*] [$($at:ident: $at_ty:ty),*]) => {
        /// The effects a camera ray may meet before the primary ray's hit `found` (if any),
        /// asked in the list's order: the sample's linear colour and whether a decision was
        /// made again exactly, from the first that shows; its outcome passed to `record` and
        /// its time to `time`.
        #[inline(always)]
        pub(crate) fn before_hit<S: $crate::arith::Scalar>(
            cx: &$crate::render::Context<'_>,
            ray: &$crate::geometry::Ray,
            found: Option<&$crate::traverse::Found<S>>,
            record: &mut impl Record,
            time: &mut EffectTime,
        ) -> Option<(glam::DVec3, bool)> {
            $(
                if <$before_ty as Sampled>::asked(cx) {
                    let start = std::time::Instant::now();
                    let shown = <$before_ty as BeforeHit>::before_hit::<S>(cx, ray, found);
                    if let Some(shown) = shown {
                        record.before_hit::<$before_ty>(&shown.outcome, &shown.queries);
                        time.$before = nanos_since(start);
                        return Some((shown.colour, shown.redone));
                    }
                }
            )*
            None
        }

        /// The effects that change the light at the hit `at` in `cx`, asked in the list's
        /// order: whether one made a decision again exactly; their outcomes passed to
        /// `record` and their times to `time`.
        #[inline(always)]
        pub(crate) fn at_hit<S: $crate::arith::Scalar>(
            cx: &$crate::render::Context<'_>,
            at: &At<'_, S>,
            light: &mut Light,
            record: &mut impl Record,
            time: &mut EffectTime,
        ) -> bool {
            let mut redone = false;
            $(
                if <$at_ty as Sampled>::asked(cx) {
                    let start = std::time::Instant::now();
                    let outcome = <$at_ty as AtHit>::at_hit::<S>(cx, at, light);
                    record.at_hit::<$at_ty>(&outcome);
                    redone |= <$at_ty as AtHit>::redone(&outcome);
                    time.$at = nanos_since(start);
                }
            )*
            redone
        }
    };
}

pub(super) use registry;
