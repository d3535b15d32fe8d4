//! `raytracer watch SCENE [--port P]`: a page on the loopback address that shows the scene's
//! render refining (one sample a pixel first, then four times more each pass) and renders again
//! when the scene file or an asset it reads changes; a scene that fails to load shows its error
//! above the last good image. Nothing is written to disk: the image is served from memory.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use clap::Parser;
use notify::Watcher as _;

use raytracer::files::shown;
use raytracer::image_io::encode_image;
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load, Scene};

use crate::batch::summary::json_string;
use crate::exit_code::{self, Failure};
use crate::image_flags::ImageFlags;
use crate::load_flags::LoadFlags;
use crate::values;

/// The page the server shows.
const PAGE: &str = include_str!("watch.html");

/// How often the server and the render look for a change or Ctrl-C.
const TICK: Duration = Duration::from_millis(50);

/// How long a change is let settle before the scene is read again (an editor may write a file
/// in several steps).
const SETTLE: Duration = Duration::from_millis(100);

/// Passes refine at least to this many samples a pixel, or to the scene's own count if larger.
const LEAST_FINAL_SPP: u32 = 16;

#[derive(Parser, Debug)]
#[command(
    name = "raytracer watch",
    about = "Shows a scene's render in the browser, refining, and renders it again whenever the scene or an asset it reads changes.",
    after_help = "Serves http://127.0.0.1:PORT/ (loopback only) until Ctrl-C; exit 0 then, 1 if the port cannot be opened, 2 usage error."
)]
struct WatchCli {
    /// The scene file (JSON).
    scene: PathBuf,
    /// The port on 127.0.0.1 (0: any free port; the address is printed).
    #[arg(long, default_value_t = 8642)]
    port: u16,
    #[command(flatten)]
    image: ImageFlags,
    #[command(flatten)]
    load: LoadFlags,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = values::thread_count())]
    threads: Option<u64>,
}

/// What the page shows: the latest image and what it is.
#[derive(Default)]
struct Shown {
    /// One more with every new image; 0 before the first.
    version: u64,
    png: Vec<u8>,
    /// Why the scene does not load now, with its place; the image stays the last good one.
    error: Option<String>,
    /// What the image is, or what is being done.
    status: String,
}

/// Flags shared by the server, the render and the file watcher.
#[derive(Clone, Default)]
struct Signals {
    /// Ctrl-C came: everything stops.
    stop: Arc<AtomicBool>,
    /// A watched file changed since the scene was last read.
    changed: Arc<AtomicBool>,
    /// The render under way stops: set with either of the others, cleared with `changed`.
    cancel: Arc<AtomicBool>,
}

/// Runs `raytracer watch` (`args` start with `watch`) and returns its exit status.
pub fn main(args: &[OsString]) -> ExitCode {
    let cli = match exit_code::parse::<WatchCli>(args) {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => failure.report(),
    }
}

/// Parses `args` as [`main`] would, without running anything.
pub(super) fn try_parse(args: &[OsString]) -> Result<(), clap::Error> {
    WatchCli::try_parse_from(args).map(|_| ())
}

/// Serves the page until Ctrl-C, with the render on a thread of its own.
fn run(cli: WatchCli) -> Result<(), Failure> {
    let pool = values::thread_pool(cli.threads).map_err(Failure::Input)?;
    let server = tiny_http::Server::http(("127.0.0.1", cli.port))
        .map_err(|e| Failure::Input(format!("cannot serve on 127.0.0.1:{}: {e}", cli.port)))?;
    let port = server.server_addr().to_ip().map_or(cli.port, |a| a.port());
    outln!("http://127.0.0.1:{port}/");
    eprintln!(
        "watching {}: open http://127.0.0.1:{port}/ (Ctrl-C to stop)",
        shown(&cli.scene)
    );
    let signals = Signals::default();
    let (stop, cancel) = (signals.stop.clone(), signals.cancel.clone());
    let _ = ctrlc::set_handler(move || {
        stop.store(true, Ordering::Relaxed);
        cancel.store(true, Ordering::Relaxed);
    });
    let shown_now = Arc::new(Mutex::new(Shown::default()));
    let name = shown(&cli.scene).to_string();
    let renderer = {
        let (shown_now, signals) = (shown_now.clone(), signals.clone());
        std::thread::spawn(move || pool.install(|| render_loop(&cli, &shown_now, &signals)))
    };
    while !signals.stop.load(Ordering::Relaxed) {
        if let Ok(Some(request)) = server.recv_timeout(TICK) {
            respond(request, &shown_now, &name);
        }
    }
    let _ = renderer.join();
    eprintln!("stopped");
    Ok(())
}

/// Answers one request: the page, the latest image, or the state as JSON.
fn respond(request: tiny_http::Request, shown_now: &Mutex<Shown>, name: &str) {
    let header = |value: &str| {
        tiny_http::Header::from_bytes(&b"Content-Type"[..], value.as_bytes())
            .expect("a valid header")
    };
    let no_store = tiny_http::Header::from_bytes(&b"Cache-Control"[..], &b"no-store"[..])
        .expect("a valid header");
    let path = request.url().split('?').next().unwrap_or("").to_string();
    let shown = shown_now.lock().unwrap_or_else(|e| e.into_inner());
    let response = match path.as_str() {
        "/" => tiny_http::Response::from_data(PAGE.as_bytes().to_vec())
            .with_header(header("text/html; charset=utf-8")),
        "/image.png" => {
            tiny_http::Response::from_data(shown.png.clone()).with_header(header("image/png"))
        }
        "/state" => tiny_http::Response::from_data(state_json(&shown, name).into_bytes())
            .with_header(header("application/json")),
        _ => tiny_http::Response::from_data(b"not found".to_vec()).with_status_code(404),
    };
    drop(shown);
    let _ = request.respond(response.with_header(no_store));
}

/// The state the page polls for.
fn state_json(shown: &Shown, name: &str) -> String {
    format!(
        "{{\"scene\":{},\"version\":{},\"status\":{},\"error\":{}}}",
        json_string(name),
        shown.version,
        json_string(&shown.status),
        shown
            .error
            .as_deref()
            .map_or("null".to_string(), json_string)
    )
}

/// Reads the scene, renders it in passes of growing sample counts and waits for a change, until
/// Ctrl-C. A scene that does not load leaves its error for the page and the last image shown.
fn render_loop(cli: &WatchCli, shown_now: &Mutex<Shown>, signals: &Signals) {
    let watched = Arc::new(Mutex::new(Vec::<PathBuf>::new()));
    let watcher = {
        let (watched, changed, cancel) = (
            watched.clone(),
            signals.changed.clone(),
            signals.cancel.clone(),
        );
        notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
            let Ok(event) = event else { return };
            let files = watched.lock().unwrap_or_else(|e| e.into_inner());
            if event.paths.iter().any(|p| files.contains(p)) {
                changed.store(true, Ordering::Relaxed);
                cancel.store(true, Ordering::Relaxed);
            }
        })
    };
    let Ok(mut watcher) = watcher else {
        set(shown_now, |s| {
            s.error = Some("cannot watch files here".into())
        });
        return;
    };
    let mut folders: Vec<PathBuf> = Vec::new();
    while !signals.stop.load(Ordering::Relaxed) {
        signals.changed.store(false, Ordering::Relaxed);
        if !signals.stop.load(Ordering::Relaxed) {
            signals.cancel.store(false, Ordering::Relaxed);
        }
        set(shown_now, |s| s.status = "reading the scene".into());
        let loaded = load(&cli.scene, &cli.load.options());
        let inputs = match &loaded {
            Ok(scene) => scene.inputs.clone(),
            Err(_) => vec![cli.scene.clone()],
        };
        watch(&mut watcher, &mut folders, &watched, &inputs);
        match loaded {
            Err(e) => set(shown_now, |s| {
                s.error = Some(e.to_string());
                s.status = "the scene does not load; the last good image is shown".into();
            }),
            Ok(scene) => {
                set(shown_now, |s| s.error = None);
                render_passes(cli, &scene, shown_now, signals);
            }
        }
        while !signals.changed.load(Ordering::Relaxed) && !signals.stop.load(Ordering::Relaxed) {
            std::thread::sleep(TICK);
        }
        std::thread::sleep(SETTLE);
    }
}

/// Watches the folders of `inputs` (editors often replace a file rather than write it) and
/// notes the files themselves, by absolute path, as the ones whose changes count.
fn watch(
    watcher: &mut notify::RecommendedWatcher,
    folders: &mut Vec<PathBuf>,
    watched: &Mutex<Vec<PathBuf>>,
    inputs: &[PathBuf],
) {
    let absolute: Vec<PathBuf> = inputs.iter().filter_map(|p| absolute(p)).collect();
    for file in &absolute {
        let Some(folder) = file.parent() else {
            continue;
        };
        if !folders.iter().any(|f| f == folder)
            && watcher
                .watch(folder, notify::RecursiveMode::NonRecursive)
                .is_ok()
        {
            folders.push(folder.to_path_buf());
        }
    }
    *watched.lock().unwrap_or_else(|e| e.into_inner()) = absolute;
}

/// `path` as the file watcher names it: its folder resolved, its own name kept.
fn absolute(path: &Path) -> Option<PathBuf> {
    let name = path.file_name()?;
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.canonicalize().ok()?,
        _ => std::env::current_dir().ok()?,
    };
    Some(folder.join(name))
}

/// Renders `scene` at 1, 4, 16, … samples a pixel up to its own count (at least
/// [`LEAST_FINAL_SPP`]), showing each pass; a change or Ctrl-C stops the pass under way.
fn render_passes(cli: &WatchCli, scene: &Scene, shown_now: &Mutex<Shown>, signals: &Signals) {
    let base = cli.image.render_options(scene);
    let last = base.spp.max(LEAST_FINAL_SPP);
    let tone_map = cli.image.tone_map(scene);
    let exposure = cli.image.display_exposure(scene);
    let mut spp = 1;
    loop {
        set(shown_now, |s| {
            s.status = format!("rendering {spp} sample{} a pixel", plural(spp))
        });
        let options = RenderOptions {
            spp,
            cancel: Some(signals.cancel.clone()),
            ..base.clone()
        };
        let out = render(scene, &options);
        let out = match out {
            Ok(out) if !out.cancelled => out,
            _ => return,
        };
        let png = encode_image(Path::new("watch.png"), &out.film, tone_map, exposure);
        set(shown_now, |s| match png {
            Ok(png) => {
                s.png = png;
                s.version += 1;
                s.status = format!(
                    "{}×{}, {spp} sample{} a pixel{}",
                    out.film.width,
                    out.film.height,
                    plural(spp),
                    if spp >= last { "" } else { ", refining" }
                );
            }
            Err(e) => s.error = Some(e.to_string()),
        });
        if spp >= last {
            return;
        }
        spp = (spp * 4).min(last);
    }
}

/// "s" unless `n` is one.
fn plural(n: u32) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// Changes what the page shows.
fn set(shown_now: &Mutex<Shown>, change: impl FnOnce(&mut Shown)) {
    change(&mut shown_now.lock().unwrap_or_else(|e| e.into_inner()));
}
