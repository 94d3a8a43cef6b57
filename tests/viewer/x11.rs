//! A private X server (Xvfb on a free display) and what a user does on it: pointer moves,
//! button presses and keys through XTEST, and screenshots of a window.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::thread::sleep;
use std::time::Duration;
use x11rb::connection::Connection;
use x11rb::protocol::xproto::{self, ConnectionExt as _, ImageFormat, InputFocus};
use x11rb::protocol::xtest::ConnectionExt as _;
use x11rb::rust_connection::RustConnection;
use x11rb::wrapper::ConnectionExt as _;

/// Xvfb on a display number it picked itself (`-displayfd`), stopped on drop.
pub struct Xvfb {
    child: Child,
    pub display: String,
}

impl Xvfb {
    pub fn start() -> Xvfb {
        Xvfb::with_screen("1600x900x24")
    }

    /// Xvfb with a screen of `size` (`WIDTHxHEIGHTxDEPTH`).
    pub fn with_screen(size: &str) -> Xvfb {
        let spawned = Command::new("Xvfb")
            .args(["-displayfd", "1", "-screen", "0", size, "-nolisten", "tcp"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn();
        let mut child = match spawned {
            Ok(child) => child,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => panic!(
                "Xvfb is not installed, and the viewer tests need it: install xvfb and the X \
                 run-time libraries (Debian: apt-get install xvfb libx11-6 libx11-xcb1 \
                 libxcursor1 libxi6 libxkbcommon-x11-0; .ci/run does this)"
            ),
            Err(e) => panic!("cannot start Xvfb: {e}"),
        };
        // Xvfb writes the display number once it accepts connections.
        let stdout = child.stdout.take().expect("piped stdout");
        let (send, receive) = mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = BufReader::new(stdout).read_line(&mut line);
            let _ = send.send(line);
        });
        let line = receive
            .recv_timeout(Duration::from_secs(20))
            .unwrap_or_default();
        let number = line.trim();
        if number.is_empty() || number.parse::<u32>().is_err() {
            let _ = child.kill();
            panic!("Xvfb did not report a display number (got {line:?})");
        }
        Xvfb {
            child,
            display: format!(":{number}"),
        }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A client connection that plays the user.
pub struct X {
    pub conn: RustConnection,
    pub root: xproto::Window,
    pub screen_size: (u16, u16),
    pub root_depth: u8,
    pub root_visual: xproto::Visualid,
    pub white: u32,
}

/// RGB pixels of a window.
pub struct Shot {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<[u8; 3]>,
}

impl X {
    pub fn connect(display: &str) -> X {
        let (conn, screen) = x11rb::connect(Some(display)).expect("connect to Xvfb");
        let s = &conn.setup().roots[screen];
        let (root, screen_size) = (s.root, (s.width_in_pixels, s.height_in_pixels));
        let (root_depth, root_visual, white) = (s.root_depth, s.root_visual, s.white_pixel);
        X {
            conn,
            root,
            screen_size,
            root_depth,
            root_visual,
            white,
        }
    }

    pub fn atom(&self, name: &str) -> xproto::Atom {
        self.conn
            .intern_atom(false, name.as_bytes())
            .expect("send InternAtom")
            .reply()
            .expect("InternAtom reply")
            .atom
    }

    /// Moves the real pointer (root coordinates).
    pub fn move_to(&self, (x, y): (i16, i16)) {
        self.fake(xproto::MOTION_NOTIFY_EVENT, 0, (x, y));
    }

    pub fn press(&self, button: u8) {
        self.fake(xproto::BUTTON_PRESS_EVENT, button, (0, 0));
    }

    pub fn release(&self, button: u8) {
        self.fake(xproto::BUTTON_RELEASE_EVENT, button, (0, 0));
    }

    /// A drag as a hand does it: move there, rest (egui decides from the previous frame's
    /// hover whether a press is its own), press, move in steps, release.
    pub fn drag(&self, from: (i16, i16), to: (i16, i16), button: u8, steps: i16) {
        self.move_to(from);
        sleep(Duration::from_millis(150));
        self.press(button);
        sleep(Duration::from_millis(40));
        for k in 1..=steps {
            let at = (
                from.0 + (to.0 - from.0) * k / steps,
                from.1 + (to.1 - from.1) * k / steps,
            );
            self.move_to(at);
            sleep(Duration::from_millis(16));
        }
        sleep(Duration::from_millis(40));
        self.release(button);
        sleep(Duration::from_millis(40));
    }

    /// Presses and releases the key that types `keysym` (e.g. `'h' as u32`).
    pub fn key(&self, keysym: u32) {
        let setup = self.conn.setup();
        let (first, count) = (setup.min_keycode, setup.max_keycode - setup.min_keycode + 1);
        let mapping = self
            .conn
            .get_keyboard_mapping(first, count)
            .expect("send GetKeyboardMapping")
            .reply()
            .expect("keyboard mapping");
        let per = usize::from(mapping.keysyms_per_keycode).max(1);
        let index = mapping
            .keysyms
            .iter()
            .position(|&k| k == keysym)
            .unwrap_or_else(|| panic!("no key types keysym {keysym:#x}"));
        let keycode = first + (index / per) as u8;
        self.fake(xproto::KEY_PRESS_EVENT, keycode, (0, 0));
        sleep(Duration::from_millis(30));
        self.fake(xproto::KEY_RELEASE_EVENT, keycode, (0, 0));
        sleep(Duration::from_millis(30));
    }

    /// Gives `window` the keyboard (there is no window manager to do it).
    pub fn focus(&self, window: u32) {
        self.conn
            .set_input_focus(InputFocus::POINTER_ROOT, window, x11rb::CURRENT_TIME)
            .expect("send SetInputFocus");
        self.conn.flush().expect("flush");
        sleep(Duration::from_millis(100));
    }

    /// Where the window's top-left corner is on the screen.
    pub fn origin(&self, window: u32) -> (i16, i16) {
        let reply = self
            .conn
            .translate_coordinates(window, self.root, 0, 0)
            .expect("send TranslateCoordinates")
            .reply()
            .expect("TranslateCoordinates reply");
        (reply.dst_x, reply.dst_y)
    }

    /// Sets the window's size, as a window manager would when the user drags its border.
    pub fn resize(&self, window: u32, (width, height): (u32, u32)) {
        let size = xproto::ConfigureWindowAux::new()
            .width(width)
            .height(height);
        self.conn
            .configure_window(window, &size)
            .expect("send ConfigureWindow");
        self.conn.flush().expect("flush");
    }

    /// The window's pixels as the X server has them.
    pub fn capture(&self, window: u32) -> Shot {
        let geometry = self
            .conn
            .get_geometry(window)
            .expect("send GetGeometry")
            .reply()
            .expect("geometry");
        self.capture_part(window, (0, 0), (geometry.width, geometry.height))
    }

    /// The pixels of a `w` x `h` rectangle of the window from `(x, y)`.
    pub fn capture_part(&self, window: u32, (x, y): (i16, i16), (w, h): (u16, u16)) -> Shot {
        let image = self
            .conn
            .get_image(ImageFormat::Z_PIXMAP, window, x, y, w, h, !0)
            .expect("send GetImage")
            .reply()
            .expect("GetImage reply");
        // 24-bit depth on Xvfb: 4 bytes a pixel, blue first.
        let rgb = image
            .data
            .chunks_exact(4)
            .map(|p| [p[2], p[1], p[0]])
            .collect();
        Shot {
            width: usize::from(w),
            height: usize::from(h),
            rgb,
        }
    }

    fn fake(&self, kind: u8, detail: u8, (x, y): (i16, i16)) {
        self.conn
            .xtest_fake_input(kind, detail, x11rb::CURRENT_TIME, self.root, x, y, 0)
            .expect("send XTEST input");
        self.conn.sync().expect("sync");
    }
}

impl Shot {
    /// Pixels of the rectangle `[x0, x1) x [y0, y1)`, clipped to the shot.
    pub fn region(&self, (x0, y0, x1, y1): (usize, usize, usize, usize)) -> Vec<[u8; 3]> {
        let mut out = Vec::new();
        for y in y0..y1.min(self.height) {
            for x in x0..x1.min(self.width) {
                out.push(self.rgb[y * self.width + x]);
            }
        }
        out
    }

    /// Saves the shot for a person to look at when a test fails.
    pub fn save(&self, path: &std::path::Path) {
        let flat: Vec<u8> = self.rgb.iter().flatten().copied().collect();
        let image = image::RgbImage::from_raw(self.width as u32, self.height as u32, flat);
        if let Some(image) = image {
            let _ = image.save(path);
        }
    }
}
