//! Timing a case's hiders in alternating rounds.
//!
//! Timing each hider's repeats back to back lets a slow moment of the
//! machine (another process, a frequency change) fall on one hider's runs
//! and not on its neighbour's, and the report then compares noise. Here
//! every hider renders once first (unmeasured unless the timer asks for no
//! warm-up: that render is the one scored and drawn on the contact sheet),
//! then the measured renders go round the hiders, one render each per
//! round, so that a disturbance touches all of them alike; each hider's
//! median is taken over its rounds.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use hider_scene::timing::{Summary, Timer};
use hider_scene::{DynHider, Frame, PrepareOptions, Scene, ScreenScene, StatsTable, View};

/// What a render needs: from the world-space scene (front end included)
/// when `whole`, else from the prepared screen scene.
pub(crate) struct RenderInput<'a> {
    pub scene: &'a Scene,
    pub view: &'a View,
    pub screen: &'a ScreenScene,
    pub whole: bool,
}

/// One hider taking part in the rounds.
pub(crate) struct Contender {
    /// The hider, kept alive across rounds so that its scratch buffers are
    /// warm, as in a frame loop.
    pub hider: Box<dyn DynHider>,
    /// The index of its row among the case's rows.
    pub row: usize,
    /// Its own copy of the screen scene for `render_scene` to fill (the
    /// real-size study), so that no round starts from another's.
    screen: Option<ScreenScene>,
    samples: Vec<Duration>,
    spent: Duration,
    /// Why it stopped early: an error or a panic in a later render.
    pub failure: Option<String>,
}

impl Contender {
    /// A contender whose first render took `first` (counted as a sample
    /// when `first_is_measured`).
    pub fn new(
        hider: Box<dyn DynHider>,
        row: usize,
        input: &RenderInput<'_>,
        first: Duration,
        first_is_measured: bool,
    ) -> Self {
        let samples = if first_is_measured {
            vec![first]
        } else {
            Vec::new()
        };
        Self {
            hider,
            row,
            screen: input.whole.then(|| input.screen.clone()),
            spent: samples.iter().sum(),
            samples,
            failure: None,
        }
    }

    /// The measured renders, summarised.
    pub fn summary(&self) -> Summary {
        Summary::of(&self.samples)
    }
}

/// Renders once into `frame`, catching errors and panics: the time taken
/// and the hider's stats, or the row's status saying why there are none.
pub(crate) fn render_once(
    hider: &mut dyn DynHider,
    input: &RenderInput<'_>,
    screen: Option<&mut ScreenScene>,
    frame: &mut Frame,
) -> Result<(Duration, StatsTable), String> {
    let prepare_options = PrepareOptions::default();
    let started = Instant::now();
    let done = catch_unwind(AssertUnwindSafe(|| match screen {
        Some(screen) if input.whole => {
            hider.render_scene(input.scene, input.view, &prepare_options, screen, frame)
        }
        _ => hider.render(input.screen, frame),
    }));
    let took = started.elapsed();
    match done {
        Ok(Ok(stats)) => Ok((took, stats)),
        Ok(Err(e)) => Err(format!("error: {e}")),
        Err(panic) => {
            let msg = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                .unwrap_or_else(|| "unknown".into());
            Err(format!("error: panicked: {msg}"))
        }
    }
}

/// The first render of a hider on a case, with its own screen scene when
/// `whole`: the warm-up (or the first measured render) and the frame that
/// is scored.
pub(crate) fn first_render(
    hider: &mut dyn DynHider,
    input: &RenderInput<'_>,
    frame: &mut Frame,
) -> Result<(Duration, StatsTable), String> {
    let mut screen = input.whole.then(|| input.screen.clone());
    render_once(hider, input, screen.as_mut(), frame)
}

/// The remaining warm-ups, then up to `timing.runs` measured renders per
/// contender, in rounds that visit every contender once; a contender stops
/// after `timing.max_seconds` of measured renders (after at least one),
/// when `stop` is set, or at its first failure.
pub(crate) fn time_in_rounds(
    contenders: &mut [Contender],
    input: &RenderInput<'_>,
    timing: &Timer,
    stop: &AtomicBool,
    frame: &mut Frame,
) {
    for c in contenders.iter_mut() {
        for _ in 1..timing.warmup {
            if stop.load(Ordering::Relaxed) {
                return;
            }
            if let Err(e) = render_once(c.hider.as_mut(), input, c.screen.as_mut(), frame) {
                c.failure = Some(e);
                break;
            }
        }
    }
    let budget = Duration::from_secs_f64(timing.max_seconds.clamp(0.0, 1e9));
    for _ in 0..timing.runs.max(1) {
        let mut any = false;
        for c in contenders.iter_mut() {
            let has_one = !c.samples.is_empty();
            if c.failure.is_some()
                || c.samples.len() >= timing.runs.max(1) as usize
                || (has_one && (c.spent > budget || stop.load(Ordering::Relaxed)))
            {
                continue;
            }
            any = true;
            match render_once(c.hider.as_mut(), input, c.screen.as_mut(), frame) {
                Ok((took, _)) => {
                    c.samples.push(took);
                    c.spent += took;
                }
                Err(e) => c.failure = Some(e),
            }
        }
        if !any {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    use std::cell::RefCell;
    use std::rc::Rc;

    use hider_scene::{OrderedPolygons, PrepareOptions, Result, View, prepare, procedural};

    use super::*;

    /// A hider that only records when it is called.
    struct Recorder {
        name: &'static str,
        calls: Rc<RefCell<Vec<&'static str>>>,
    }

    impl DynHider for Recorder {
        fn name(&self) -> &str {
            self.name
        }
        fn render(&mut self, _: &ScreenScene, _: &mut Frame) -> Result<StatsTable> {
            self.calls.borrow_mut().push(self.name);
            Ok(StatsTable::default())
        }
        fn render_scene(
            &mut self,
            _: &Scene,
            _: &View,
            _: &PrepareOptions,
            _: &mut ScreenScene,
            _: &mut Frame,
        ) -> Result<StatsTable> {
            self.calls.borrow_mut().push(self.name);
            Ok(StatsTable::default())
        }
        fn check_size(&self, _: u32, _: u32) -> Result<()> {
            Ok(())
        }
        fn resolves_color(&self) -> bool {
            false
        }
        fn composites_transparency(&self) -> bool {
            false
        }
        fn ordered_polygons(&self) -> Option<&dyn OrderedPolygons> {
            None
        }
    }

    #[test]
    fn measured_renders_alternate_between_the_hiders() {
        let scene = procedural::cube();
        let view = View::for_scene(&scene, 8, 8).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let input = RenderInput {
            scene: &scene,
            view: &view,
            screen: &screen,
            whole: false,
        };
        let calls = Rc::new(RefCell::new(Vec::new()));
        let mut contenders: Vec<Contender> = ["a", "b"]
            .into_iter()
            .enumerate()
            .map(|(k, name)| {
                let hider = Recorder {
                    name,
                    calls: calls.clone(),
                };
                Contender::new(Box::new(hider), k, &input, Duration::ZERO, false)
            })
            .collect();
        let mut frame = Frame::new(8, 8).unwrap();
        let timing = Timer::new(3).with_warmup(2);
        time_in_rounds(
            &mut contenders,
            &input,
            &timing,
            &AtomicBool::new(false),
            &mut frame,
        );
        // One more warm-up each (the first render was the other), then
        // three rounds visiting both.
        assert_eq!(*calls.borrow(), ["a", "b", "a", "b", "a", "b", "a", "b"]);
        assert!(contenders.iter().all(|c| c.summary().runs == 3));

        // With no warm-up the first render is the first sample: two more.
        calls.borrow_mut().clear();
        let mut one = vec![Contender::new(
            Box::new(Recorder {
                name: "c",
                calls: calls.clone(),
            }),
            0,
            &input,
            Duration::from_millis(1),
            true,
        )];
        time_in_rounds(
            &mut one,
            &input,
            &Timer::new(3).with_warmup(0),
            &AtomicBool::new(false),
            &mut frame,
        );
        assert_eq!(*calls.borrow(), ["c", "c"]);
        assert_eq!(one[0].summary().runs, 3);
    }
}
