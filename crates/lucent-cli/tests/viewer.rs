//! `lucent view` in a real window: under Xvfb, the window appears, a screenshot of it taken
//! through the X server shows the scene, and a close request ends the process with status 0.
//!
//! Skipped, with a note, where Xvfb is not installed (`apt-get install xvfb`), unless
//! LUCENT_REQUIRE_TOOLS is set (as `.ci/run` does after installing it).
#![cfg(feature = "viewer")]

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};
use x11rb::connection::Connection;
use x11rb::protocol::xproto::{
    self, AtomEnum, ClientMessageEvent, ConnectionExt, EventMask, ImageFormat, MapState, Window,
};
use x11rb::protocol::xtest::ConnectionExt as _;
use x11rb::rust_connection::RustConnection;

/// Ends and reaps its process when dropped: neither Xvfb nor the viewer outlives the test,
/// even when an assertion fails. SIGTERM first, so that Xvfb removes its socket and lock
/// file; SIGKILL if it is still there a second later.
struct Reaped(Child);

impl Drop for Reaped {
    fn drop(&mut self) {
        if let Ok(None) = self.0.try_wait() {
            let _ = Command::new("kill").arg(self.0.id().to_string()).status();
            let deadline = Instant::now() + Duration::from_secs(1);
            while Instant::now() < deadline && matches!(self.0.try_wait(), Ok(None)) {
                std::thread::sleep(Duration::from_millis(10));
            }
        }
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn find_in_path(tool: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join(tool))
        .find(|p| p.is_file())
}

/// Starts Xvfb on a free display; returns it and the display's number.
fn start_xvfb(xvfb: &Path) -> (Reaped, u32) {
    for n in 90..130 {
        let socket = PathBuf::from(format!("/tmp/.X11-unix/X{n}"));
        if socket.exists() || Path::new(&format!("/tmp/.X{n}-lock")).exists() {
            continue;
        }
        let child = Command::new(xvfb)
            .args([
                &format!(":{n}"),
                "-screen",
                "0",
                "800x600x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("Xvfb starts");
        let mut server = Reaped(child);
        let deadline = Instant::now() + Duration::from_secs(10);
        while Instant::now() < deadline {
            if socket.exists() {
                return (server, n);
            }
            // Exited: another server took the number first; try the next.
            if server.0.try_wait().ok().flatten().is_some() {
                break;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }
    panic!("no free X display number in :90..:130 for Xvfb");
}

/// The mapped top-level window whose title starts `lucent view`, with its size.
fn find_window(conn: &RustConnection, root: Window) -> Option<(Window, u16, u16)> {
    let tree = conn.query_tree(root).ok()?.reply().ok()?;
    let net_wm_name = conn
        .intern_atom(false, b"_NET_WM_NAME")
        .ok()?
        .reply()
        .ok()?
        .atom;
    for w in tree.children {
        let titled = [AtomEnum::WM_NAME.into(), net_wm_name].iter().any(|&name| {
            conn.get_property(false, w, name, AtomEnum::ANY, 0, 1024)
                .ok()
                .and_then(|c| c.reply().ok())
                .is_some_and(|p| p.value.starts_with("lucent view".as_bytes()))
        });
        let mapped = conn
            .get_window_attributes(w)
            .ok()
            .and_then(|c| c.reply().ok())
            .is_some_and(|a| a.map_state == MapState::VIEWABLE);
        if titled && mapped {
            let g = conn.get_geometry(w).ok()?.reply().ok()?;
            return Some((w, g.width, g.height));
        }
    }
    None
}

/// The window's pixels as RGB, through the X server (a 24-bit screen stores 32 bits a pixel,
/// blue first).
fn screenshot(conn: &RustConnection, w: Window, width: u16, height: u16) -> Vec<[u8; 3]> {
    let image = conn
        .get_image(ImageFormat::Z_PIXMAP, w, 0, 0, width, height, !0)
        .unwrap()
        .reply()
        .unwrap();
    assert_eq!(image.depth, 24, "the Xvfb screen is 24 bits deep");
    assert_eq!(
        image.data.len(),
        usize::from(width) * usize::from(height) * 4
    );
    image
        .data
        .chunks_exact(4)
        .map(|p| [p[2], p[1], p[0]])
        .collect()
}

/// What the screenshot shows, enough to tell the default scene from a black or uniform window.
#[derive(Debug)]
struct Looks {
    distinct: usize,
    std_dev: f64,
    /// Shares of the window: the sky's blue, the checkerboard's red and its yellow.
    sky: f64,
    red: f64,
    yellow: f64,
}

fn looks(pixels: &[[u8; 3]]) -> Looks {
    let n = pixels.len() as f64;
    let mut distinct: Vec<u32> = pixels
        .iter()
        .map(|p| u32::from_be_bytes([0, p[0], p[1], p[2]]))
        .collect();
    distinct.sort_unstable();
    distinct.dedup();
    let luma: Vec<f64> = pixels
        .iter()
        .map(|p| (f64::from(p[0]) + f64::from(p[1]) + f64::from(p[2])) / 3.0)
        .collect();
    let mean = luma.iter().sum::<f64>() / n;
    let var = luma.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / n;
    let share = |f: &dyn Fn(i32, i32, i32) -> bool| {
        pixels
            .iter()
            .filter(|p| f(i32::from(p[0]), i32::from(p[1]), i32::from(p[2])))
            .count() as f64
            / n
    };
    Looks {
        distinct: distinct.len(),
        std_dev: var.sqrt(),
        sky: share(&|r, g, b| b > r + 60 && b > g + 20),
        red: share(&|r, g, b| r > 120 && r > g + 80 && r > b + 80),
        yellow: share(&|r, g, b| r > 150 && g > 110 && b < g - 60),
    }
}

impl Looks {
    fn is_the_default_scene(&self) -> bool {
        self.distinct >= 100
            && self.std_dev > 20.0
            && self.sky > 0.1
            && self.red > 0.03
            && self.yellow > 0.03
    }
}

/// The window's title (`_NET_WM_NAME`, UTF-8).
fn title(conn: &RustConnection, w: Window) -> String {
    let name = conn
        .intern_atom(false, b"_NET_WM_NAME")
        .unwrap()
        .reply()
        .unwrap()
        .atom;
    let p = conn
        .get_property(false, w, name, AtomEnum::ANY, 0, 1024)
        .unwrap()
        .reply()
        .unwrap();
    String::from_utf8_lossy(&p.value).into_owned()
}

/// Input as a person gives it, through the XTEST extension.
struct Person<'a> {
    conn: &'a RustConnection,
    root: Window,
}

impl Person<'_> {
    fn send(&self, kind: u8, detail: u8, (x, y): (i16, i16)) {
        self.conn
            .xtest_fake_input(kind, detail, 0, self.root, x, y, 0)
            .unwrap();
        self.conn.flush().unwrap();
    }

    fn move_to(&self, at: (i16, i16)) {
        self.send(xproto::MOTION_NOTIFY_EVENT, 0, at);
        std::thread::sleep(Duration::from_millis(15));
    }

    /// Left-drags from `from` by `dx` pixels, in steps as a hand would.
    fn drag(&self, from: (i16, i16), dx: i16) {
        self.move_to(from);
        self.send(xproto::BUTTON_PRESS_EVENT, 1, from);
        for i in 1..=10 {
            self.move_to((from.0 + dx * i / 10, from.1));
        }
        self.send(xproto::BUTTON_RELEASE_EVENT, 1, (from.0 + dx, from.1));
    }

    /// Presses and releases the key that types `keysym` (a Latin-1 letter's code).
    fn tap(&self, keysym: u32) {
        let setup = self.conn.setup();
        let (first, count) = (setup.min_keycode, setup.max_keycode - setup.min_keycode + 1);
        let map = self
            .conn
            .get_keyboard_mapping(first, count)
            .unwrap()
            .reply()
            .unwrap();
        let per = usize::from(map.keysyms_per_keycode);
        let index = map
            .keysyms
            .chunks(per)
            .position(|syms| syms.contains(&keysym))
            .expect("the keyboard has the key");
        let code = first + index as u8;
        self.send(xproto::KEY_PRESS_EVENT, code, (0, 0));
        std::thread::sleep(Duration::from_millis(15));
        self.send(xproto::KEY_RELEASE_EVENT, code, (0, 0));
    }
}

/// The share of pixels that differ by more than a little between two screenshots.
fn changed(a: &[[u8; 3]], b: &[[u8; 3]]) -> f64 {
    let far = |p: &[u8; 3], q: &[u8; 3]| p.iter().zip(q).any(|(x, y)| x.abs_diff(*y) > 24);
    a.iter().zip(b).filter(|(p, q)| far(p, q)).count() as f64 / a.len() as f64
}

/// Polls `f` every 50 ms until it holds, for at most `seconds`.
fn within(seconds: u64, mut f: impl FnMut() -> bool) -> bool {
    let deadline = Instant::now() + Duration::from_secs(seconds);
    while Instant::now() < deadline {
        if f() {
            return true;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    false
}

fn save_png(path: &Path, pixels: &[[u8; 3]], width: u16, height: u16) {
    let bytes: Vec<u8> = pixels.iter().flatten().copied().collect();
    image::save_buffer(
        path,
        &bytes,
        u32::from(width),
        u32::from(height),
        image::ColorType::Rgb8,
    )
    .unwrap();
}

#[test]
fn the_viewer_shows_the_scene_under_xvfb_and_closes_on_request() {
    let Some(xvfb) = find_in_path("Xvfb") else {
        assert!(
            std::env::var("LUCENT_REQUIRE_TOOLS").is_err(),
            "Xvfb is required (LUCENT_REQUIRE_TOOLS is set) but not installed"
        );
        eprintln!("skipped: Xvfb is not installed (apt-get install xvfb)");
        return;
    };
    let started = Instant::now();
    let (_server, display) = start_xvfb(&xvfb);
    let root_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut viewer = Reaped(
        Command::new(env!("CARGO_BIN_EXE_lucent"))
            .args(["view", "examples/whitted.toml", "--threads", "2"])
            .current_dir(&root_dir)
            .env("DISPLAY", format!(":{display}"))
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("lucent starts"),
    );
    let (conn, screen) = x11rb::connect(Some(&format!(":{display}"))).expect("Xvfb answers");
    let root = conn.setup().roots[screen].root;

    // The window appears…
    let deadline = Instant::now() + Duration::from_secs(20);
    let (window, width, height) = loop {
        if let Some(found) = find_window(&conn, root) {
            break found;
        }
        if let Some(status) = viewer.0.try_wait().unwrap() {
            let out = viewer.0.wait_with_output_lossy();
            panic!("lucent view exited ({status}) before its window appeared: {out}");
        }
        assert!(Instant::now() < deadline, "no lucent window within 20 s");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert_eq!(
        (width, height),
        (800, 600),
        "the window takes the scene's size"
    );

    // …and fills with the scene: sky, and both colours of the checkerboard.
    let deadline = Instant::now() + Duration::from_secs(15);
    let shot = Path::new(env!("CARGO_TARGET_TMPDIR")).join("viewer-screenshot.png");
    let before = loop {
        std::thread::sleep(Duration::from_millis(250));
        let pixels = screenshot(&conn, window, width, height);
        let l = looks(&pixels);
        if l.is_the_default_scene() {
            save_png(&shot, &pixels, width, height);
            break pixels;
        }
        if Instant::now() > deadline {
            save_png(&shot, &pixels, width, height);
            panic!(
                "the window does not show the default scene: {l:?} (screenshot: {})",
                shot.display()
            );
        }
    };

    // A drag orbits the camera: the picture turns.
    let person = Person { conn: &conn, root };
    person.drag((300, 300), 150);
    let mut after = Vec::new();
    let turned = within(5, || {
        after = screenshot(&conn, window, width, height);
        changed(&before, &after) > 0.3
    });
    let orbited = Path::new(env!("CARGO_TARGET_TMPDIR")).join("viewer-orbited.png");
    save_png(&orbited, &after, width, height);
    assert!(
        turned,
        "a drag did not turn the picture: {:.0}% of pixels changed (after: {})",
        100.0 * changed(&before, &after),
        orbited.display()
    );
    // The title reads the mode, the sample rate and the oldest pixel's age; M changes mode.
    assert!(
        within(3, || title(&conn, window)
            .contains("samples/s — oldest pixel")),
        "the title has no readout: {}",
        title(&conn, window)
    );
    assert!(title(&conn, window).contains("frameless"));
    // Focus goes to the window, as a window manager gives it on a click (Xvfb has none).
    conn.set_input_focus(xproto::InputFocus::PARENT, window, x11rb::CURRENT_TIME)
        .unwrap();
    conn.flush().unwrap();
    std::thread::sleep(Duration::from_millis(100));
    person.tap(u32::from(b'm'));
    assert!(
        within(3, || title(&conn, window).contains("adaptive")),
        "M did not switch frameless to adaptive: {}",
        title(&conn, window)
    );

    // A close request, as a window manager sends it, ends the process cleanly.
    let atom = |name: &[u8]| conn.intern_atom(false, name).unwrap().reply().unwrap().atom;
    let (protocols, delete) = (atom(b"WM_PROTOCOLS"), atom(b"WM_DELETE_WINDOW"));
    let close = ClientMessageEvent::new(32, window, protocols, [delete, 0, 0, 0, 0]);
    conn.send_event(false, window, EventMask::NO_EVENT, close)
        .unwrap();
    conn.flush().unwrap();
    let deadline = Instant::now() + Duration::from_secs(5);
    let status = loop {
        if let Some(status) = viewer.0.try_wait().unwrap() {
            break status;
        }
        assert!(
            Instant::now() < deadline,
            "lucent view still runs 5 s after the close request"
        );
        std::thread::sleep(Duration::from_millis(20));
    };
    let out = viewer.0.wait_with_output_lossy();
    assert!(status.success(), "lucent view exited with {status}: {out}");
    assert!(out.contains("samples/s"), "{out}");
    eprintln!(
        "viewer test: {:.1} s; {out}",
        started.elapsed().as_secs_f64()
    );
}

trait OutputLossy {
    fn wait_with_output_lossy(&mut self) -> String;
}

impl OutputLossy for Child {
    /// The process's stdout and stderr (it has exited).
    fn wait_with_output_lossy(&mut self) -> String {
        use std::io::Read;
        let mut text = String::new();
        for pipe in [
            self.stdout.take().map(|p| Box::new(p) as Box<dyn Read>),
            self.stderr.take().map(|p| Box::new(p) as Box<dyn Read>),
        ]
        .into_iter()
        .flatten()
        {
            let mut pipe = pipe;
            let _ = pipe.read_to_string(&mut text);
        }
        text
    }
}
