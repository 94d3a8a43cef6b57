//! A drag source speaking XDND version 5, as a file manager does: it presses the mouse on a
//! small "file icon" window of its own, drags the real pointer to the target (the icon keeps
//! the implicit pointer grab, so the target sees no motion, only XDND messages), offers
//! `text/uri-list`, serves the target's selection request, releases and drops, then waits
//! for XdndFinished.

use super::x11::X;
use std::path::Path;
use std::thread::sleep;
use std::time::{Duration, Instant};
use x11rb::connection::Connection;
use x11rb::protocol::xproto::{
    self, AtomEnum, ClientMessageEvent, ConnectionExt as _, CreateWindowAux, EventMask, PropMode,
    SelectionNotifyEvent, WindowClass,
};
use x11rb::protocol::Event;
use x11rb::wrapper::ConnectionExt as _;

const VERSION: u32 = 5;

/// How a drag ended.
#[derive(Debug, PartialEq, Eq)]
pub enum Outcome {
    /// XdndFinished with the accept bit.
    Accepted,
    /// Refused, left on purpose, or no answer in time.
    NotAccepted(String),
}

struct Atoms {
    aware: u32,
    enter: u32,
    position: u32,
    status: u32,
    leave: u32,
    drop: u32,
    finished: u32,
    selection: u32,
    action_copy: u32,
    type_list: u32,
    targets: u32,
    uri_list: u32,
    timestamp: u32,
}

impl Atoms {
    fn intern(x: &X) -> Atoms {
        let atom = |name| x.atom(name);
        Atoms {
            aware: atom("XdndAware"),
            enter: atom("XdndEnter"),
            position: atom("XdndPosition"),
            status: atom("XdndStatus"),
            leave: atom("XdndLeave"),
            drop: atom("XdndDrop"),
            finished: atom("XdndFinished"),
            selection: atom("XdndSelection"),
            action_copy: atom("XdndActionCopy"),
            type_list: atom("XdndTypeList"),
            targets: atom("TARGETS"),
            uri_list: atom("text/uri-list"),
            timestamp: atom("_HEIGHTRAY_TEST_TIME"),
        }
    }
}

/// The "file icon" the drag starts on: a small override-redirect window offering
/// `text/uri-list`, watching its own properties (for server timestamps).
fn icon_window(x: &X, atoms: &Atoms) -> u32 {
    let window = x.conn.generate_id().expect("an X id");
    let (sx, sy) = source_position(x);
    let aux = CreateWindowAux::new()
        .background_pixel(x.white)
        .override_redirect(1)
        .event_mask(
            EventMask::PROPERTY_CHANGE | EventMask::BUTTON_PRESS | EventMask::BUTTON_RELEASE,
        );
    x.conn
        .create_window(
            x.root_depth,
            window,
            x.root,
            sx - 20,
            sy - 20,
            40,
            40,
            0,
            WindowClass::INPUT_OUTPUT,
            x.root_visual,
            &aux,
        )
        .expect("create the icon window");
    x.conn
        .change_property32(
            PropMode::REPLACE,
            window,
            atoms.type_list,
            AtomEnum::ATOM,
            &[atoms.uri_list],
        )
        .expect("set XdndTypeList");
    x.conn.map_window(window).expect("map the icon");
    x.conn.sync().expect("sync");
    window
}

/// The drag source: its icon window and what the target has said.
struct Source<'a> {
    x: &'a X,
    atoms: Atoms,
    window: u32,
    uris: Vec<u8>,
    status_accepted: Option<bool>,
    finished: Option<bool>,
    served: usize,
}

/// Drags `file` from the bottom-left corner of the screen to `at` (root coordinates) and
/// drops it there; with `leave`, hovers over the target and leaves again instead.
pub fn drag_file(x: &X, file: &Path, at: (i16, i16), leave: bool) -> Outcome {
    drag_files(x, &[file], at, leave)
}

/// Drags `files` together, as a file manager drags a selection, and drops them at `at`.
pub fn drag_files(x: &X, files: &[&Path], at: (i16, i16), leave: bool) -> Outcome {
    let mut source = Source::new(x, files);
    let outcome = source.run(at, leave);
    let _ = x.conn.destroy_window(source.window);
    let _ = x.conn.flush();
    outcome
}

impl<'a> Source<'a> {
    fn new(x: &'a X, files: &[&Path]) -> Source<'a> {
        let atoms = Atoms::intern(x);
        let uris = files
            .iter()
            .map(|file| {
                let path = std::fs::canonicalize(file).expect("the dropped file exists");
                format!("file://{}\r\n", percent_encode(&path.to_string_lossy()))
            })
            .collect::<String>()
            .into_bytes();
        let window = icon_window(x, &atoms);
        Source {
            x,
            atoms,
            window,
            uris,
            status_accepted: None,
            finished: None,
            served: 0,
        }
    }

    fn run(&mut self, at: (i16, i16), leave: bool) -> Outcome {
        let time = self.server_time();
        self.x
            .conn
            .set_selection_owner(self.window, self.atoms.selection, time)
            .expect("own XdndSelection");
        let from = source_position(self.x);
        self.x.move_to(from);
        sleep(Duration::from_millis(50));
        // The press lands on the icon, which keeps the pointer grabbed for the whole drag.
        self.x.press(1);
        sleep(Duration::from_millis(50));
        let target = self.drag_over(from, at);
        let Some(target) = target else {
            self.x.release(1);
            return Outcome::NotAccepted("no XdndAware window at the drop point".into());
        };
        // Let the target fetch the data it asked for at the first position.
        self.pump(Duration::from_secs(2), |s| s.served > 0);
        self.x.release(1);
        if leave || self.status_accepted != Some(true) {
            self.send(target, self.atoms.leave, [self.window, 0, 0, 0, 0]);
            self.pump(Duration::from_millis(300), |_| false);
            let why = if leave {
                "left on purpose"
            } else {
                "target did not accept"
            };
            return Outcome::NotAccepted(why.into());
        }
        let time = self.server_time();
        self.send(target, self.atoms.drop, [self.window, 0, time, 0, 0]);
        self.pump(Duration::from_secs(10), |s| s.finished.is_some());
        match self.finished {
            Some(true) => Outcome::Accepted,
            Some(false) => Outcome::NotAccepted("XdndFinished without accept".into()),
            None => Outcome::NotAccepted("no XdndFinished".into()),
        }
    }

    /// Moves the pointer to `at` in steps, entering the aware window under it and sending a
    /// position for each step (waiting for the status, as a real source does).
    fn drag_over(&mut self, from: (i16, i16), at: (i16, i16)) -> Option<u32> {
        let steps = 12;
        let mut entered: Option<u32> = None;
        for k in 1..=steps {
            let p = (
                from.0 + (at.0 - from.0) * k / steps,
                from.1 + (at.1 - from.1) * k / steps,
            );
            self.x.move_to(p);
            let target = self.aware_window_at(p);
            if target != entered {
                if let Some(old) = entered {
                    self.send(old, self.atoms.leave, [self.window, 0, 0, 0, 0]);
                }
                if let Some(new) = target {
                    let flags = VERSION << 24;
                    self.send(
                        new,
                        self.atoms.enter,
                        [self.window, flags, self.atoms.uri_list, 0, 0],
                    );
                    self.status_accepted = None;
                }
                entered = target;
            }
            if let Some(target) = entered {
                let time = self.server_time();
                let packed = ((p.0 as u32) << 16) | (p.1 as u32 & 0xffff);
                let data = [self.window, 0, packed, time, self.atoms.action_copy];
                self.send(target, self.atoms.position, data);
                self.pump(Duration::from_secs(1), |s| s.status_accepted.is_some());
            }
            self.pump(Duration::from_millis(20), |_| false);
        }
        entered
    }

    /// The XdndAware window under root point `p`, walking down the window tree.
    fn aware_window_at(&self, p: (i16, i16)) -> Option<u32> {
        let mut window = self.x.root;
        loop {
            if window != self.x.root && window != self.window && self.is_aware(window) {
                return Some(window);
            }
            let reply = self
                .x
                .conn
                .translate_coordinates(self.x.root, window, p.0, p.1)
                .ok()?
                .reply()
                .ok()?;
            if reply.child == x11rb::NONE {
                return None;
            }
            window = reply.child;
        }
    }

    fn is_aware(&self, window: u32) -> bool {
        let reply = self
            .x
            .conn
            .get_property(false, window, self.atoms.aware, AtomEnum::ATOM, 0, 1)
            .ok()
            .and_then(|cookie| cookie.reply().ok());
        reply.is_some_and(|r| r.value_len > 0)
    }

    fn send(&self, target: u32, message: u32, data: [u32; 5]) {
        let event = ClientMessageEvent::new(32, target, message, data);
        self.x
            .conn
            .send_event(false, target, EventMask::NO_EVENT, event)
            .expect("send a ClientMessage");
        self.x.conn.flush().expect("flush");
    }

    /// A real server timestamp (selections must not use CurrentTime).
    fn server_time(&mut self) -> u32 {
        self.x
            .conn
            .change_property8(
                PropMode::REPLACE,
                self.window,
                self.atoms.timestamp,
                AtomEnum::STRING,
                b"t",
            )
            .expect("touch a property");
        self.x.conn.flush().expect("flush");
        let deadline = Instant::now() + Duration::from_secs(2);
        while Instant::now() < deadline {
            match self.x.conn.poll_for_event() {
                Ok(Some(Event::PropertyNotify(e))) if e.atom == self.atoms.timestamp => {
                    return e.time
                }
                Ok(Some(event)) => self.handle(event),
                Ok(None) => sleep(Duration::from_millis(2)),
                Err(e) => panic!("X connection failed: {e}"),
            }
        }
        x11rb::CURRENT_TIME
    }

    /// Handles events until `done` or the timeout.
    fn pump(&mut self, timeout: Duration, done: impl Fn(&Self) -> bool) {
        let deadline = Instant::now() + timeout;
        while !done(self) && Instant::now() < deadline {
            match self.x.conn.poll_for_event() {
                Ok(Some(event)) => self.handle(event),
                Ok(None) => sleep(Duration::from_millis(2)),
                Err(e) => panic!("X connection failed: {e}"),
            }
        }
    }

    fn handle(&mut self, event: Event) {
        match event {
            Event::SelectionRequest(request) if request.selection == self.atoms.selection => {
                self.serve(request)
            }
            Event::ClientMessage(message) => {
                let data = message.data.as_data32();
                if message.type_ == self.atoms.status {
                    self.status_accepted = Some(data[1] & 1 == 1);
                } else if message.type_ == self.atoms.finished {
                    self.finished = Some(data[1] & 1 == 1);
                }
            }
            _ => {}
        }
    }

    /// Answers the target's request for the dragged data (or for the list of types).
    fn serve(&mut self, request: xproto::SelectionRequestEvent) {
        let conn = &self.x.conn;
        let property = if request.property == x11rb::NONE {
            request.target
        } else {
            request.property
        };
        let answered = if request.target == self.atoms.targets {
            let types = [self.atoms.uri_list, self.atoms.targets];
            conn.change_property32(
                PropMode::REPLACE,
                request.requestor,
                property,
                AtomEnum::ATOM,
                &types,
            )
            .is_ok()
        } else if request.target == self.atoms.uri_list {
            self.served += 1;
            conn.change_property8(
                PropMode::REPLACE,
                request.requestor,
                property,
                request.target,
                &self.uris,
            )
            .is_ok()
        } else {
            false
        };
        let notify = SelectionNotifyEvent {
            response_type: xproto::SELECTION_NOTIFY_EVENT,
            sequence: 0,
            time: request.time,
            requestor: request.requestor,
            selection: request.selection,
            target: request.target,
            property: if answered { property } else { x11rb::NONE },
        };
        let _ = conn.send_event(false, request.requestor, EventMask::NO_EVENT, notify);
        let _ = conn.flush();
    }
}

/// Where the drag starts: the bottom-left corner of the screen, outside the viewer.
fn source_position(x: &X) -> (i16, i16) {
    (30, x.screen_size.1 as i16 - 30)
}

/// A path as the URI path part: unreserved characters and `/` stay, the rest is %XX.
fn percent_encode(path: &str) -> String {
    path.bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'/' | b'-' | b'_' | b'.' | b'~' => {
                (b as char).to_string()
            }
            _ => format!("%{b:02X}"),
        })
        .collect()
}
