//! Loading terrains off the window's thread: built-ins, height map files and scene files,
//! read, decoded and built into acceleration data on a background thread. A newer load
//! supersedes an older one: the older one's result is dropped when it arrives.

use super::mailbox::Mailbox;
use super::sources;
use super::state::{LoadEvent, LoadFailure, LoadRequest, Loaded, Progress, Stage};
use std::any::Any;
use std::panic::AssertUnwindSafe;
use std::sync::Arc;
use std::time::Instant;

/// Loads on one background thread, newest first: a request made while another is loading
/// waits (replacing any request already waiting), and the superseded load's result is
/// dropped when it arrives. Loads cannot stop halfway, and running them side by side would
/// only split the CPU (and memory) between work of which just the newest counts.
pub struct Loader {
    shared: Arc<Shared>,
    in_flight: Option<(u64, Progress)>,
}

struct Shared {
    requests: Mailbox<LoadRequest>,
    sink: Box<dyn Fn(LoadEvent) + Send + Sync>,
}

impl Loader {
    /// `sink` receives the loading thread's events (it wakes the window).
    pub fn new(sink: impl Fn(LoadEvent) + Send + Sync + 'static) -> std::io::Result<Loader> {
        let shared = Arc::new(Shared {
            requests: Mailbox::new(),
            sink: Box::new(sink),
        });
        let thread_shared = Arc::clone(&shared);
        std::thread::Builder::new()
            .name("heightray-load".into())
            .spawn(move || load_loop(&thread_shared))?;
        Ok(Loader {
            shared,
            in_flight: None,
        })
    }

    /// Queues a load, superseding any load in progress or waiting.
    pub fn start(&mut self, request: LoadRequest) {
        let label = request.label();
        let generation = self.shared.requests.post(request);
        let progress = Progress {
            label,
            stage: Stage::Reading,
            started: Instant::now(),
        };
        self.in_flight = Some((generation, progress));
    }

    /// Takes a loading thread's event; returns the result of the newest load when it is done,
    /// with the name of what was loaded.
    pub fn accept(&mut self, event: LoadEvent) -> Option<(String, Result<Loaded, LoadFailure>)> {
        let newest = self.shared.requests.newest();
        match event {
            LoadEvent::Stage { generation, stage } if generation == newest => {
                if let Some((_, progress)) = &mut self.in_flight {
                    progress.stage = stage;
                }
                None
            }
            LoadEvent::Done { generation, result } if generation == newest => {
                let label = self
                    .in_flight
                    .take()
                    .map(|(_, p)| p.label)
                    .unwrap_or_default();
                Some((label, *result))
            }
            _ => None,
        }
    }

    /// The load in progress, if any.
    pub fn progress(&self) -> Option<&Progress> {
        self.in_flight.as_ref().map(|(_, p)| p)
    }
}

impl Drop for Loader {
    fn drop(&mut self) {
        // The thread finishes the load it is in (it cannot stop halfway) and then ends.
        self.shared.requests.close();
    }
}

/// The loading thread: waits for the newest request and loads it.
fn load_loop(shared: &Shared) {
    while let Some((generation, request)) = shared.requests.take() {
        let report = |stage| {
            // A superseded load says nothing more; its result is dropped anyway.
            if shared.requests.newest() == generation {
                (shared.sink)(LoadEvent::Stage { generation, stage });
            }
        };
        // A newer request cancels this load while the file is decoded.
        let superseded = || shared.requests.newest() != generation;
        let label = request.label();
        // A load that panics is reported as failed, and the thread goes on to the next
        // request: a window whose loader died would show "loading" for every later file.
        let loaded = std::panic::catch_unwind(AssertUnwindSafe(|| {
            sources::load(request, &report, &superseded)
        }));
        let result = Box::new(loaded.unwrap_or_else(|panic| {
            Err(LoadFailure::Internal {
                label,
                message: panic_message(panic.as_ref()).to_owned(),
            })
        }));
        (shared.sink)(LoadEvent::Done { generation, result });
    }
}

/// What a panic said, if it said it in words.
fn panic_message(panic: &(dyn Any + Send)) -> &str {
    panic
        .downcast_ref::<&str>()
        .copied()
        .or_else(|| panic.downcast_ref::<String>().map(String::as_str))
        .unwrap_or("no message")
}

/// Loads on the calling thread (for the terrain named on the command line).
pub fn load_now(request: LoadRequest) -> Result<Loaded, LoadFailure> {
    sources::load(request, &|_| {}, &|| false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::state::{Decoding, Source};
    use std::path::PathBuf;
    use std::sync::{mpsc, Mutex};
    use std::time::Duration;

    /// Starts the requests one after the other; returns the result the window would take.
    fn run_all(requests: Vec<LoadRequest>) -> Result<Loaded, LoadFailure> {
        let (send, receive) = mpsc::channel();
        let send = Mutex::new(send);
        let mut loader = Loader::new(move |event| {
            let _ = send.lock().map(|s| s.send(event));
        })
        .expect("a loading thread");
        for request in requests {
            loader.start(request);
        }
        loop {
            let event = receive.recv().expect("the loading thread reports");
            if let Some((_, result)) = loader.accept(event) {
                return result;
            }
        }
    }

    fn run(request: LoadRequest) -> Result<Loaded, LoadFailure> {
        run_all(vec![request])
    }

    fn builtin(z_scale: f64) -> LoadRequest {
        LoadRequest {
            source: Source::Builtin("small49"),
            z_scale: Some(z_scale),
            reframe: true,
            from_memory: None,
            decoding: Decoding::default(),
            overlay: None,
        }
    }

    fn file(path: PathBuf) -> LoadRequest {
        LoadRequest {
            source: Source::File(path),
            z_scale: None,
            reframe: true,
            from_memory: None,
            decoding: Decoding::default(),
            overlay: None,
        }
    }

    #[test]
    fn the_newest_load_wins() {
        let loaded = run_all(vec![builtin(1.0), builtin(2.0), builtin(3.0)]).expect("loads");
        assert_eq!(loaded.terrain.field().z_scale(), 3.0);
    }

    #[test]
    fn loads_a_builtin_and_rescales_it() {
        let loaded = run(builtin(3.0)).expect("small49 loads");
        assert_eq!(loaded.terrain.field().width(), 49);
        assert_eq!(loaded.terrain.field().z_scale(), 3.0);
    }

    #[test]
    fn a_file_that_is_not_an_image_is_an_error_message() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("notes.txt");
        std::fs::write(&path, "not a height map").expect("write");
        let error = run(file(path)).err().expect("refused").to_string();
        assert!(error.contains("not a PNG, PGM or TIFF"), "{error}");
    }

    #[test]
    fn a_newer_request_stops_the_reading_of_a_file() {
        let dir = tempfile::tempdir().expect("temp dir");
        // 400 MB of samples (zeros that take no disk space), then a small map.
        let big = dir.path().join("big.pgm");
        let head = b"P5 20000 20000 255\n";
        std::fs::write(&big, head).expect("write");
        let opened = std::fs::OpenOptions::new().write(true).open(&big);
        opened
            .and_then(|f| f.set_len(head.len() as u64 + 400_000_000))
            .expect("a sparse file");
        let small = dir.path().join("ramp.pgm");
        std::fs::write(&small, "P2 3 2 255\n0 1 2\n3 4 5\n").expect("write");

        let (send, receive) = mpsc::channel();
        let send = Mutex::new(send);
        let (go_on, wait) = mpsc::channel::<()>();
        let wait = Mutex::new(wait);
        // The first load, about to read, waits until the newer request has been made.
        let mut loader = Loader::new(move |event| {
            let reading = matches!(event, LoadEvent::Stage { generation: 1, .. });
            let _ = send.lock().map(|s| s.send(event));
            if reading {
                let _ = wait.lock().map(|w| w.recv());
            }
        })
        .expect("a loading thread");
        loader.start(file(big));
        let receive = |what| {
            receive
                .recv_timeout(Duration::from_secs(10))
                .unwrap_or_else(|_| panic!("no {what} within 10 s"))
        };
        assert!(matches!(
            receive("stage"),
            LoadEvent::Stage { generation: 1, .. }
        ));
        loader.start(file(small));
        go_on.send(()).expect("the loading thread waits");
        let (mut first, mut newest) = (None, None);
        while first.is_none() || newest.is_none() {
            match receive("result") {
                LoadEvent::Done {
                    generation: 1,
                    result,
                } => first = Some(*result),
                event => newest = loader.accept(event).or(newest),
            }
        }
        let first = first
            .and_then(Result::err)
            .expect("the first load stopped")
            .to_string();
        assert!(first.contains("big.pgm was cancelled"), "{first}");
        let (label, newest) = newest.expect("the newest load's result");
        assert_eq!(label, "ramp.pgm");
        assert_eq!(newest.expect("ramp.pgm loads").terrain.field().width(), 3);
    }

    #[test]
    fn a_plain_image_gets_a_quarter_of_its_side_as_z_scale() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("ramp.pgm");
        std::fs::write(
            &path,
            "P2\n8 4\n255\n".to_owned() + &"0 1 2 3 4 5 6 7\n".repeat(4),
        )
        .expect("write");
        let loaded = run(file(path)).expect("loads");
        assert_eq!(loaded.terrain.field().z_scale(), 2.0);
    }

    #[test]
    fn an_image_in_metres_gets_its_range_scaled_to_a_quarter_of_its_side() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("tile.png");
        // Mapbox terrain-RGB, 40x8: heights 250 m to 2200 m along x.
        let image = image::RgbImage::from_fn(40, 8, |x, _| {
            let code = (250.0 + 50.0 * f64::from(x) + 10000.0) as u32 * 10;
            image::Rgb([(code >> 16) as u8, (code >> 8) as u8, code as u8])
        });
        image.save(&path).expect("write");
        let loaded = run(LoadRequest {
            source: Source::File(path),
            z_scale: None,
            reframe: true,
            from_memory: None,
            decoding: Decoding {
                colour: crate::heightfield::ColourEncoding::Mapbox,
                nodata: crate::heightfield::NoDataValue::Off,
                height_unit: None,
            },
            overlay: None,
        })
        .expect("loads");
        let (lo, hi) = loaded.terrain.z_range();
        assert!((hi - lo - 10.0).abs() < 1e-9, "relief {lo} .. {hi}");
        // Still the same shape: heights in proportion to the metres.
        assert!((hi / lo - 2200.0 / 250.0).abs() < 1e-9, "{lo} .. {hi}");
    }
}
