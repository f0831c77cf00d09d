//! Shadow methods run in rounds, for backends that answer occluder questions only in
//! batches (a GPU answers thousands of shadow beams in one dispatch, not one at a time).
//!
//! A [`ShadowMethod`] asks its [`Occluders`] one question at a time and decides what to ask
//! next from the answers. To batch those questions without writing each method twice, every
//! query's method is *replayed*: questions answered in an earlier round are answered from
//! the query's memo; an unanswered one is recorded and given a provisional answer (a beam
//! rejected, a segment free) so that the method goes on and reveals the other questions
//! it would ask regardless. The recorded questions of every query form the next batch. A
//! replay that asks nothing new used true answers only: its result is the method's result,
//! exactly as if the questions had been answered one by one, and its counters are those
//! of the questions it used. Provisional answers never reach a result.
//!
//! The methods' loops over sub-beams and samples ask every question in the first replay
//! that reaches them, so the beam method takes three batches (the initial beams, the
//! sub-beams, nothing), the quadtree one batch per level. Methods that need single-object
//! searches (the stochastic method's last-occluder cache) are refused: the caller's
//! backend says it does not support them.

use std::collections::HashMap;

use glam::DVec3;
use rayon::prelude::*;

use super::{
    BeamStart, LightVisibility, Occluders, Occlusion, Patch, ShadowMethod, ShadowQuery, ShadowWork,
    hard::Visibility,
};
use crate::beam::BoxClass;
use crate::root::RootCounters;

/// A question a shadow method asks its occluders.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Question {
    /// [`Occluders::segment`]: the segment `from → to` for `t ∈ [start, 1]`.
    Segment {
        /// Start point.
        from: DVec3,
        /// End point (on the light).
        to: DVec3,
        /// Where the search starts.
        start: f64,
    },
    /// [`Occluders::beam`]: the shadow beam from `from` over `light` for `t ∈ [start, 1]`.
    Beam {
        /// The point.
        from: DVec3,
        /// The light, or a part of it.
        light: Patch,
        /// Where the search starts.
        start: f64,
        /// Whether the inclusion test runs (to prove umbra).
        inclusion: bool,
    },
}

/// The answer to a [`Question`] (of the same kind).
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Answer {
    /// A segment's occlusion.
    Segment(Occlusion),
    /// A beam's class.
    Beam(BoxClass),
}

/// The bits of a question: equal questions have equal keys.
type Key = [u64; 14];

impl Question {
    fn key(&self) -> Key {
        let mut k = [0u64; 14];
        let put = |k: &mut Key, at: usize, v: DVec3| {
            k[at] = v.x.to_bits();
            k[at + 1] = v.y.to_bits();
            k[at + 2] = v.z.to_bits();
        };
        match *self {
            Question::Segment { from, to, start } => {
                put(&mut k, 1, from);
                put(&mut k, 4, to);
                k[13] = start.to_bits();
            }
            Question::Beam {
                from,
                light,
                start,
                inclusion,
            } => {
                k[0] = 1 + u64::from(inclusion);
                put(&mut k, 1, from);
                put(&mut k, 4, light.corner);
                put(&mut k, 7, light.edge_u);
                put(&mut k, 10, light.edge_v);
                k[13] = start.to_bits();
            }
        }
        k
    }
}

/// Why a method could not run in rounds.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum RoundsError<E> {
    /// The method asked for single-object searches, which batches do not answer.
    NeedsObjects,
    /// The replays did not settle within the round limit.
    TooManyRounds,
    /// Answering a batch failed.
    Answer(E),
}

/// The most rounds a query may take.
pub const MAX_ROUNDS: usize = 4096;

/// One replay of a method: answers from the memo, provisional answers for the rest.
struct Replay<'m> {
    memo: &'m HashMap<Key, (Answer, RootCounters)>,
    asked: Vec<Question>,
    objects: bool,
}

impl Replay<'_> {
    fn ask(&mut self, q: Question, c: &mut RootCounters) -> Option<Answer> {
        match self.memo.get(&q.key()) {
            Some((a, search)) => {
                c.add(search);
                Some(*a)
            }
            None => {
                self.asked.push(q);
                None
            }
        }
    }
}

impl Occluders for Replay<'_> {
    fn segment(&mut self, from: DVec3, to: DVec3, start: f64, c: &mut RootCounters) -> Occlusion {
        match self.ask(Question::Segment { from, to, start }, c) {
            Some(Answer::Segment(o)) => o,
            _ => Occlusion {
                visibility: Visibility::Lit,
                at: None,
            },
        }
    }

    fn object_at(&mut self, _p: DVec3) -> u32 {
        self.objects = true;
        0
    }

    fn segment_meets_object(&mut self, _: u32, _: DVec3, _: DVec3, _: &mut RootCounters) -> bool {
        self.objects = true;
        false
    }

    fn beam(
        &mut self,
        from: DVec3,
        light: &Patch,
        start: BeamStart,
        inclusion: bool,
        c: &mut RootCounters,
    ) -> BoxClass {
        let q = Question::Beam {
            from,
            light: *light,
            start: start.at(),
            inclusion,
        };
        match self.ask(q, c) {
            Some(Answer::Beam(b)) => b,
            _ => BoxClass::Miss,
        }
    }
}

/// The visible fraction of each query's light by `method`, the questions answered in
/// batches by `answer` (one answer per question, in order, with its search counters).
///
/// # Errors
///
/// [`RoundsError`]: the method needs single-object searches, it did not settle, or
/// `answer` failed.
pub fn visibility_in_rounds<E>(
    method: &dyn ShadowMethod,
    queries: &[ShadowQuery],
    mut answer: impl FnMut(&[Question]) -> Result<Vec<(Answer, RootCounters)>, E>,
) -> Result<(Vec<LightVisibility>, ShadowWork), RoundsError<E>> {
    let n = queries.len();
    let mut memos: Vec<HashMap<Key, (Answer, RootCounters)>> = vec![HashMap::new(); n];
    let mut results: Vec<Option<(LightVisibility, ShadowWork)>> = vec![None; n];
    let mut active: Vec<usize> = (0..n).collect();
    let mut rounds = 0;
    while !active.is_empty() {
        rounds += 1;
        if rounds > MAX_ROUNDS {
            return Err(RoundsError::TooManyRounds);
        }
        type Replayed = (usize, LightVisibility, ShadowWork, Vec<Question>, bool);
        let replays: Vec<Replayed> = active
            .par_iter()
            .map(|&i| {
                let mut r = Replay {
                    memo: &memos[i],
                    asked: Vec::new(),
                    objects: false,
                };
                let mut work = ShadowWork::default();
                let lv = method.visibility(&mut r, &queries[i], &mut work);
                (i, lv, work, r.asked, r.objects)
            })
            .collect();
        let mut pending: Vec<Question> = Vec::new();
        let mut owners: Vec<usize> = Vec::new();
        let mut next = Vec::new();
        for (i, lv, work, asked, objects) in replays {
            if objects {
                return Err(RoundsError::NeedsObjects);
            }
            if asked.is_empty() {
                results[i] = Some((lv, work));
                continue;
            }
            let mut seen = std::collections::HashSet::new();
            for q in asked {
                if seen.insert(q.key()) {
                    pending.push(q);
                    owners.push(i);
                }
            }
            next.push(i);
        }
        if !pending.is_empty() {
            let answers = answer(&pending).map_err(RoundsError::Answer)?;
            for ((q, &i), a) in pending.iter().zip(&owners).zip(answers) {
                memos[i].insert(q.key(), a);
            }
        }
        active = next;
    }
    let mut work = ShadowWork::default();
    let visibility = results
        .into_iter()
        .map(|r| {
            let (lv, w) = r.unwrap_or((LightVisibility::estimate(0.0), ShadowWork::default()));
            work.add(&w);
            lv
        })
        .collect();
    Ok((visibility, work))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shadow::ShadowSpec;
    use interval_core::Interval;

    /// Occluders whose answers are a fixed pseudo-random function of the question.
    struct Fake;

    impl Fake {
        fn answer(q: &Question) -> (Answer, RootCounters) {
            let h = q.key().iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &x| {
                (h ^ x).wrapping_mul(0x0100_0000_01b3)
            });
            let c = RootCounters {
                g_evals: h % 7,
                bisections: h % 3,
                ..RootCounters::default()
            };
            let a = match *q {
                Question::Segment { .. } => Answer::Segment(Occlusion {
                    visibility: if h % 2 == 0 {
                        Visibility::Lit
                    } else {
                        Visibility::Occluded
                    },
                    at: (h % 2 == 1).then_some(0.5),
                }),
                Question::Beam {
                    start, inclusion, ..
                } => Answer::Beam(match h % 3 {
                    0 => BoxClass::Miss,
                    1 if inclusion => BoxClass::Hit {
                        t_final: Interval::new_unchecked(0.5, 0.6),
                    },
                    _ => BoxClass::Undecided {
                        t: Interval::new_unchecked(start + 0.01, start + 0.02),
                    },
                }),
            };
            (a, c)
        }
    }

    impl Occluders for Fake {
        fn segment(
            &mut self,
            from: DVec3,
            to: DVec3,
            start: f64,
            c: &mut RootCounters,
        ) -> Occlusion {
            let (a, s) = Fake::answer(&Question::Segment { from, to, start });
            c.add(&s);
            match a {
                Answer::Segment(o) => o,
                Answer::Beam(_) => unreachable!(),
            }
        }
        fn object_at(&mut self, _: DVec3) -> u32 {
            0
        }
        fn segment_meets_object(
            &mut self,
            _: u32,
            _: DVec3,
            _: DVec3,
            _: &mut RootCounters,
        ) -> bool {
            false
        }
        fn beam(
            &mut self,
            from: DVec3,
            light: &Patch,
            start: BeamStart,
            inclusion: bool,
            c: &mut RootCounters,
        ) -> BoxClass {
            let q = Question::Beam {
                from,
                light: *light,
                start: start.at(),
                inclusion,
            };
            let (a, s) = Fake::answer(&q);
            c.add(&s);
            match a {
                Answer::Beam(b) => b,
                Answer::Segment(_) => unreachable!(),
            }
        }
    }

    fn queries() -> Vec<ShadowQuery> {
        (0..40)
            .map(|i| ShadowQuery {
                origin: DVec3::new(f64::from(i) * 0.1, 0.2, -0.3),
                normal: DVec3::Y,
                light: Patch::square(DVec3::new(0.0, 4.0, 0.0), 1.0, 1),
                seed: u64::from(i as u32),
            })
            .collect()
    }

    #[test]
    fn rounds_give_exactly_the_one_by_one_results_and_counters() {
        for spec in [
            "beam:4",
            "beam-all:3",
            "beam-quadtree:5",
            "minkowski:beam:4",
            "minkowski:stochastic:9",
            "stochastic:16",
            "certified:0.1:64",
            "certified:0.5",
        ] {
            let spec: ShadowSpec = spec.parse().unwrap();
            let method = spec.method();
            let qs = queries();
            let mut direct = Vec::new();
            let mut direct_work = ShadowWork::default();
            for q in &qs {
                let mut w = ShadowWork::default();
                direct.push(method.visibility(&mut Fake, q, &mut w));
                direct_work.add(&w);
            }
            let mut batches = 0;
            let (batched, work) = visibility_in_rounds(&*method, &qs, |b| {
                batches += 1;
                Ok::<_, ()>(b.iter().map(Fake::answer).collect())
            })
            .unwrap();
            assert_eq!(batched, direct, "{spec}");
            assert_eq!(work, direct_work, "{spec}");
            assert!(batches >= 1, "{spec}");
        }
    }

    #[test]
    fn the_beam_method_takes_two_batches() {
        let method = "beam:4".parse::<ShadowSpec>().unwrap().method();
        let mut sizes = Vec::new();
        visibility_in_rounds(&*method, &queries(), |b| {
            sizes.push(b.len());
            Ok::<_, ()>(b.iter().map(Fake::answer).collect())
        })
        .unwrap();
        assert_eq!(sizes.len(), 2, "{sizes:?}");
        assert_eq!(sizes[0], 40);
        assert_eq!(sizes[1] % 16, 0);
    }

    #[test]
    fn the_last_occluder_cache_is_refused() {
        let method = "stochastic:8:cache".parse::<ShadowSpec>().unwrap().method();
        let r = visibility_in_rounds(&*method, &queries(), |b| {
            Ok::<_, ()>(b.iter().map(Fake::answer).collect())
        });
        assert!(matches!(r, Err(RoundsError::NeedsObjects)));
    }
}
