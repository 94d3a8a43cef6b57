//! Paths that are not height map files, typed into the path field or dropped: each is refused
//! at once with a message that says what it names, and the terrain on screen stays.

use super::{xdnd, Session};
use serde_json::Value;

/// Waits for the error about `name` and checks that it says `what` and the terrain stayed.
fn assert_refused(session: &mut Session, shown: &Value, name: &str, what: &str) {
    let refused = session.viewer.wait_for("the message about the path", |s| {
        s["error"].as_str().is_some_and(|e| e.contains(name))
    });
    let error = refused["error"].as_str().unwrap_or_default();
    assert!(
        error.contains(what) && error.contains("not a file") && error.contains("Still showing"),
        "{error}"
    );
    assert_eq!(
        refused["terrain"], shown["terrain"],
        "the terrain must stay"
    );
    assert_eq!(refused["loading"], Value::Null, "{refused}");
}

#[test]
fn a_device_a_fifo_and_a_directory_are_refused_and_the_terrain_stays() {
    let mut session = Session::start(&[]);
    // The path field is in the Heightmap section, which starts closed.
    let shown = session.open_section("heightmap_section", "open_path");

    // A device typed into the path field: reading it would never end.
    session.click(&shown, "open_path");
    session.x.focus(session.window);
    for c in "/dev/zero".chars() {
        session.x.key(c as u32);
    }
    session.x.key(0xff0d); // Return
    assert_refused(&mut session, &shown, "/dev/zero", "is a character device");

    // A FIFO and a directory dropped: opening the FIFO would wait for a writer.
    let at = session.screen(session.view_centre(&shown));
    let fifo = session.viewer.path("pipe.png");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("run mkfifo");
    assert!(made.success(), "mkfifo failed");
    let folder = session.viewer.path("maps");
    std::fs::create_dir(&folder).expect("a directory");
    for (path, what) in [(&fifo, "is a FIFO"), (&folder, "is a directory")] {
        assert_eq!(
            xdnd::drag_file(&session.x, path, at, false),
            xdnd::Outcome::Accepted
        );
        let name = path.display().to_string();
        assert_refused(&mut session, &shown, &name, what);
    }
}
