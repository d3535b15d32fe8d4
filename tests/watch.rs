//! `raytracer watch`, used as a person would: the page loaded in headless Chromium shows the
//! render, shows the new picture after the scene is edited, shows the error (file, line, column)
//! above the last good image after the scene is broken, and Ctrl-C ends the server cleanly.
//!
//! Needs Debian's `chromium` (`.ci/run` installs it); without it the test says so and passes,
//! unless `RAYTRACER_REQUIRE_CHROMIUM` is set, as CI sets it.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A small 2021–23 scene, `WIDTH` pixels wide.
fn scene(width: u32) -> String {
    format!(
        r#"{{ "nbounces": 1,
  "camera": {{ "type": "pinhole", "width": {width}, "height": 24, "fov": 45,
              "position": [0, 0, 4], "lookat": [0, 0, -1], "up": [0, 1, 0] }},
  "scene": {{ "backgroundcolor": [0.1, 0.1, 0.2],
    "lightsources": [ {{ "type": "pointlight", "position": [2, 2, 2], "intensity": [1, 1, 1] }} ],
    "shapes": [ {{ "type": "sphere", "center": [0, 0, 0], "radius": 1,
                  "material": {{ "kd": 0.8, "diffusecolor": [0.9, 0.3, 0.2] }} }} ] }} }}"#
    )
}

/// The Chromium binary, if one is installed.
fn chromium() -> Option<PathBuf> {
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .filter_map(|name| {
            std::env::var_os("PATH")?
                .to_str()?
                .split(':')
                .map(|dir| Path::new(dir).join(name))
                .find(|p| p.is_file())
        })
        .next()
}

/// The page at `url` after its scripts have run for a few seconds of virtual time.
fn page(browser: &Path, url: &str) -> String {
    let out = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--virtual-time-budget=3000",
            "--dump-dom",
            url,
        ])
        .output()
        .expect("run chromium");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The body of `GET path` on the server at `port`.
fn get(port: u16, path: &str) -> String {
    let mut stream = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    write!(stream, "GET {path} HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n").unwrap();
    let mut text = String::new();
    let _ = stream.read_to_string(&mut text);
    text.split_once("\r\n\r\n")
        .map_or(String::new(), |(_, body)| body.to_string())
}

/// Polls the server's state until `ready` holds of it (at most 30 s); the last state.
fn wait_for(port: u16, ready: impl Fn(&str) -> bool) -> String {
    let start = Instant::now();
    loop {
        let state = get(port, "/state");
        if ready(&state) || start.elapsed() > Duration::from_secs(30) {
            return state;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// The number after `"version":` in a state.
fn version(state: &str) -> u64 {
    state
        .split("\"version\":")
        .nth(1)
        .and_then(|rest| rest.split(|c: char| !c.is_ascii_digit()).next())
        .and_then(|n| n.parse().ok())
        .unwrap_or(0)
}

/// Starts `raytracer watch` on `scene` on any free port: the process and its port.
fn start(scene: &Path) -> (Child, u16) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .args(["watch", "--port", "0", "--threads", "1"])
        .arg(scene)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start raytracer watch");
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let port = line
        .trim()
        .trim_end_matches('/')
        .rsplit(':')
        .next()
        .and_then(|p| p.parse().ok())
        .unwrap_or_else(|| panic!("no address in {line:?}"));
    (child, port)
}

#[test]
fn the_page_follows_edits_shows_errors_and_ctrl_c_stops_the_server() {
    let Some(browser) = chromium() else {
        assert!(
            std::env::var_os("RAYTRACER_REQUIRE_CHROMIUM").is_none(),
            "RAYTRACER_REQUIRE_CHROMIUM is set and no chromium is installed"
        );
        eprintln!("no chromium installed: the browser test of `raytracer watch` did not run");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scene.json");
    std::fs::write(&file, scene(32)).unwrap();
    let (mut child, port) = start(&file);
    let url = format!("http://127.0.0.1:{port}/");

    // The first picture, in the page.
    let state = wait_for(port, |s| s.contains("16 samples a pixel\""));
    assert!(version(&state) >= 1, "{state}");
    let html = page(&browser, &url);
    assert!(
        html.contains("data-width=\"32\""),
        "no 32-pixel image in:\n{html}"
    );

    // The scene edited: a new picture, 48 pixels wide.
    std::fs::write(&file, scene(48)).unwrap();
    let state = wait_for(port, |s| s.contains("48×24, 16 samples a pixel\""));
    assert!(state.contains("\"error\":null"), "{state}");
    let html = page(&browser, &url);
    assert!(
        html.contains("data-width=\"48\""),
        "no 48-pixel image in:\n{html}"
    );

    // The scene broken: its error and place on the page, the last picture kept.
    std::fs::write(&file, "{ \"camera\": \n").unwrap();
    let state = wait_for(port, |s| !s.contains("\"error\":null"));
    assert!(state.contains("scene.json:2:"), "{state}");
    let html = page(&browser, &url);
    assert!(
        html.contains("scene.json:2:") && html.contains("invalid JSON"),
        "no error in:\n{html}"
    );
    assert!(
        html.contains("data-width=\"48\""),
        "the last image went:\n{html}"
    );

    // Ctrl-C: the server ends by itself, with success, and leaves nothing in the folder.
    unsafe {
        libc::kill(child.id() as libc::pid_t, libc::SIGINT);
    }
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > Duration::from_secs(10) {
            let _ = child.kill();
            panic!("the server did not stop within 10 s of Ctrl-C");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(status.success(), "{status:?}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}
