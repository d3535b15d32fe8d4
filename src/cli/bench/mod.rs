//! `raytracer bench`: Table 1 (every scene with every accelerator), or with a flag the ray
//! throughput, the `auto` crossover or a scene's ray queries by kind, printed as a table and
//! optionally written as CSV.

use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use clap::Parser;

use raytracer::accel::{Accel, AccelKind};
use raytracer::files::output::{Outputs, PendingFile};
use raytracer::files::shown;
use raytracer::scene::{load, LoadOptions};

mod crossover;
mod kinds;
mod rays;
mod scenes;
mod table;
mod timing;

use crossover::crossover;
use rays::{throughput, Throughput};
use scenes::{default_scenes_dir, sphere_grid_triangles};
use table::{format_csv, format_table, row_fields, table1, TableOptions, TABLE_HEADER};
use timing::ms;

use crate::interrupt::Interrupt;
use crate::{exit_code, values};

#[derive(Parser, Debug)]
#[command(
    name = "raytracer bench",
    about = "Benchmarks. Without options: \"Table 1\", six scenes (the bundled example and demo, \
             sphere grids from 8k to 1.2M triangles) with point and area lights, rendered with \
             every --accel mode.",
    after_help = "Timings are medians of --runs runs. Rows with --accel none or flat whose renders are \
                  estimated (from a short sample) to take longer than --none-limit seconds in all \
                  are skipped and show the estimate."
)]
struct BenchCli {
    /// Smoke run: small scenes and images, one run each (a few seconds).
    #[arg(long)]
    quick: bool,
    /// Runs per measurement; medians are reported.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=1000))]
    runs: u32,
    /// Also write the table as CSV to this file.
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Ray throughput on the sphere grids (G=4,S=16 and G=16,S=32) with the binary, four-wide and
    /// eight-wide SAH trees: build time, and primary, shadow and incoherent rays on one thread and
    /// on all. A tree whose queries use AVX2 on this CPU (the eight-wide one) is measured again
    /// with the baseline instructions (the simd column).
    #[arg(long, conflicts_with = "crossover")]
    rays: bool,
    /// With --rays: also the 8,388,610-triangle grid (G=32, S=64), once (needs about 2 GB).
    #[arg(long, requires = "rays")]
    huge: bool,
    /// With --rays: also write each grid's triangles and ray sets to this folder as raw
    /// little-endian f32 files, for another renderer to trace the same rays
    /// (benches/peers/embree.py).
    #[arg(long, value_name = "DIR", requires = "rays")]
    export: Option<PathBuf>,
    /// Time each accelerator (none, flat, sah, sah4) on random scenes of 1 to 64 primitives.
    #[arg(long)]
    crossover: bool,
    /// A scene's ray queries by kind (camera, reflection, refraction, shadow) on one thread, with
    /// the accelerator its render builds: rays, hits, Mrays/s and ns per ray.
    #[arg(long, value_name = "SCENE", num_args = 1.., conflicts_with_all = ["crossover", "rays"])]
    kinds: Vec<PathBuf>,
    /// With --kinds: the accelerator (default: what a render builds, `auto`).
    #[arg(long, requires = "kinds", default_value_t = AccelKind::Auto)]
    accel: AccelKind,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=4096))]
    threads: Option<u32>,
    /// Most primitives per BVH leaf.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u64).range(1..=255))]
    leaf_size: u64,
    /// Folder holding example.json and demo.json (default: ./scenes, else the source tree's).
    #[arg(long)]
    scenes: Option<PathBuf>,
    /// Skip `none` and `flat` rows estimated to take longer than this many seconds (at most 1 with --quick).
    #[arg(long, default_value_t = 60.0)]
    none_limit: f64,
}

/// Parses the subcommand's command line without running it.
pub(super) fn try_parse(args: &[std::ffi::OsString]) -> Result<(), clap::Error> {
    <BenchCli as Parser>::try_parse_from(args).map(drop)
}

/// Runs `raytracer bench` (`args` start with the subcommand's name) and returns its exit status.
pub fn main(args: &[OsString]) -> ExitCode {
    let cli = match exit_code::parse::<BenchCli>(args) {
        Ok(c) => c,
        Err(code) => return code,
    };
    if !(cli.none_limit >= 0.0 && cli.none_limit.is_finite()) {
        eprintln!("error: --none-limit must be a finite number of seconds, at least 0");
        return ExitCode::from(exit_code::USAGE);
    }
    let pool = match values::thread_pool(cli.threads.map(u64::from)) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(exit_code::BAD_INPUT);
        }
    };
    let interrupt = Interrupt::install("no CSV written");
    match pool.install(|| run(&cli, &interrupt)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(exit_code::BAD_INPUT)
        }
    }
}

impl BenchCli {
    /// The runs each median is of: `--runs`, or one for a smoke run.
    fn median_runs(&self) -> usize {
        if self.quick {
            1
        } else {
            self.runs as usize
        }
    }
}

/// What a benchmark prints: a header and rows of fields, shown as a fixed-width table and
/// written as CSV.
struct TextTable {
    header: Vec<&'static str>,
    rows: Vec<Vec<String>>,
}

/// Runs the benchmark the flags choose, prints its table and writes the CSV.
fn run(cli: &BenchCli, interrupt: &Interrupt) -> Result<(), String> {
    let csv_out = match &cli.csv {
        Some(path) => Some(create_csv(cli, path, interrupt)?),
        None => None,
    };
    let table = if cli.crossover {
        crossover_table(cli)
    } else if !cli.kinds.is_empty() {
        kinds_table(cli)?
    } else if cli.rays {
        throughput_table(cli)?
    } else {
        table1_text(cli)?
    };
    out!("{}", format_table(&table.header, &table.rows));
    std::io::stdout().flush().map_err(|e| e.to_string())?;
    if let Some(pending) = csv_out {
        interrupt
            .commit(pending, format_csv(&table.header, &table.rows).as_bytes())
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Claims and creates the CSV at `path` before the benchmarks run: it may not be one of the
/// bundled scenes the table reads (or anything they use), nor a `--kinds` scene.
fn create_csv(cli: &BenchCli, path: &Path, interrupt: &Interrupt) -> Result<PendingFile, String> {
    let scenes = cli.scenes.clone().unwrap_or_else(default_scenes_dir);
    let mut inputs: Vec<PathBuf> = std::fs::read_dir(&scenes)
        .map(|entries| entries.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    inputs.extend(cli.kinds.iter().cloned());
    Outputs::from_inputs(inputs.iter().map(PathBuf::as_path))
        .claim(path)
        .map_err(|e| e.to_string())?;
    interrupt.create(path).map_err(|e| e.to_string())
}

/// `--crossover`: the query times of each accelerator on sparse and backdrop scenes of growing
/// size, and their ratios.
fn crossover_table(cli: &BenchCli) -> TextTable {
    let (runs, leaf_size) = (cli.median_runs(), cli.leaf_size as usize);
    outln!(
        "auto crossover: ray queries (primary 320x240, shadow, incoherent) on one thread, \
         median of {runs}; sparse = objects in space, backdrop = a quad behind them fills \
         the view"
    );
    let sizes: &[usize] = if cli.quick {
        &[1, 8, 32]
    } else {
        &[1, 2, 3, 4, 5, 6, 7, 8, 10, 12, 16, 24, 32, 48, 64]
    };
    let header = vec![
        "prims",
        "scene",
        "none_ms",
        "flat_ms",
        "sah_ms",
        "sah4_ms",
        "flat/none",
        "sah/flat",
        "sah4/flat",
    ];
    let mut rows = Vec::new();
    for (backdrop, name) in [(false, "sparse"), (true, "backdrop")] {
        for (n, [none, flat, sah, sah4]) in crossover(sizes, backdrop, runs, leaf_size) {
            let ratio = |a: Duration, b: Duration| {
                format!("{:.2}", a.as_secs_f64() / b.as_secs_f64().max(1e-12))
            };
            rows.push(vec![
                n.to_string(),
                name.to_string(),
                format!("{:.3}", ms(none)),
                format!("{:.3}", ms(flat)),
                format!("{:.3}", ms(sah)),
                format!("{:.3}", ms(sah4)),
                ratio(flat, none),
                ratio(sah, flat),
                ratio(sah4, flat),
            ]);
        }
    }
    TextTable { header, rows }
}

/// `--kinds`: each scene's ray queries by kind, with the accelerator `--accel` resolves to.
fn kinds_table(cli: &BenchCli) -> Result<TextTable, String> {
    let runs = cli.median_runs();
    outln!(
        "ray queries by kind: from every pixel centre, the camera ray and the rays its hit \
         spawns (up to {} shadow rays a light); one thread, medians of {runs}",
        kinds::SHADOW_SAMPLES_PER_LIGHT
    );
    let header = vec![
        "scene",
        "accel",
        "kind",
        "rays",
        "hits",
        "ms",
        "mrays_s",
        "ns_per_ray",
    ];
    let mut rows = Vec::new();
    for path in &cli.kinds {
        let scene = load(path, &LoadOptions::default()).map_err(|e| e.to_string())?;
        let kind = cli.accel.resolved();
        let accel = Accel::build(&scene.primitives, kind, cli.leaf_size as usize);
        let rays = kinds::kind_rays(&scene, &accel);
        for t in kinds::time_kinds(&scene, &accel, &rays, runs) {
            let opt = |v: Option<f64>, digits: usize| {
                v.map_or_else(|| "-".to_string(), |v| format!("{v:.digits$}"))
            };
            rows.push(vec![
                shown(path).to_string(),
                kind.name().to_string(),
                t.kind.to_string(),
                t.rays.to_string(),
                t.hits.to_string(),
                format!("{:.2}", ms(t.time)),
                opt(t.mrays(), 2),
                opt(t.ns_per_ray(), 1),
            ]);
        }
    }
    Ok(TextTable { header, rows })
}

/// `--rays`: ray throughput on the sphere grids, each grid printed as it is done.
fn throughput_table(cli: &BenchCli) -> Result<TextTable, String> {
    let (runs, leaf_size) = (cli.median_runs(), cli.leaf_size as usize);
    let threads = rayon::current_num_threads();
    let mut grids: Vec<(u32, u32, usize)> = if cli.quick {
        vec![(2, 8, 1)]
    } else {
        vec![(4, 16, runs), (16, 32, runs)]
    };
    if cli.huge {
        grids.push((32, 64, 1));
    }
    outln!(
        "ray throughput: sphere grids at 640x480, leaf size {leaf_size}, {threads} thread(s), \
         medians of {runs} (the G=32 grid: one run)"
    );
    let mut rows = Vec::new();
    for (g, s, n) in grids {
        eprintln!(
            "grid G={g} S={s}: {} triangles…",
            sphere_grid_triangles(g, s)
        );
        let t = throughput(g, s, n, leaf_size, cli.export.as_deref())?;
        if let Some(dir) = &cli.export {
            eprintln!(
                "grid G={g} S={s}: triangles and rays written to {}",
                shown(dir)
            );
        }
        print_throughput(&t, threads);
        rows.extend(throughput_rows(&t, threads));
    }
    Ok(TextTable {
        header: THROUGHPUT_HEADER.to_vec(),
        rows,
    })
}

/// Without a mode flag: Table 1, each row shown on stderr as it is done.
fn table1_text(cli: &BenchCli) -> Result<TextTable, String> {
    let (runs, leaf_size) = (cli.median_runs(), cli.leaf_size as usize);
    let threads = rayon::current_num_threads();
    let options = TableOptions {
        quick: cli.quick,
        runs,
        scenes_dir: cli.scenes.clone().unwrap_or_else(default_scenes_dir),
        leaf_size,
        // A smoke run skips anything slow.
        none_limit: Duration::from_secs_f64(if cli.quick {
            cli.none_limit.min(1.0)
        } else {
            cli.none_limit
        }),
        estimate_budget: Duration::from_millis(if cli.quick { 50 } else { 500 }),
    };
    outln!(
        "Table 1: 1 spp, {threads} thread(s), leaf size {leaf_size}, medians of {runs} run(s); \
         memory = accelerator + primitive records ({} B each; none for the triangles of \
         meshes of over {} faces)",
        std::mem::size_of::<raytracer::geometry::Primitive>(),
        raytracer::geometry::primitives::RECORD_MESH_MAX_FACES,
    );
    let rows = table1(&options, |r| {
        eprintln!("  {}", row_fields(r).join(" "));
    })?;
    Ok(TextTable {
        header: TABLE_HEADER.to_vec(),
        rows: rows.iter().map(|r| row_fields(r).to_vec()).collect(),
    })
}

/// The columns of `--rays`: one row per grid, tree and ray set (and the render).
const THROUGHPUT_HEADER: [&str; 14] = [
    "grid",
    "tris",
    "accel",
    "simd",
    "build_ms",
    "median_build_ms",
    "bytes_per_tri",
    "set",
    "rays",
    "hits",
    "mrays_1t",
    "mrays_nt",
    "speedup",
    "threads",
];

/// The rows of [`THROUGHPUT_HEADER`] for one grid.
fn throughput_rows(t: &Throughput, threads: usize) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    for tree in &t.trees {
        let head = vec![
            format!("G{}S{}", t.g, t.s),
            t.triangles.to_string(),
            tree.kind.name().to_string(),
            tree.isa.name().to_string(),
            format!("{:.1}", ms(tree.build)),
            format!("{:.1}", ms(t.build_median_split)),
            format!(
                "{:.1}",
                (tree.accel_bytes + t.primitive_bytes) as f64 / t.triangles as f64
            ),
        ];
        let row = |set: &str, rays: u64, hits: String, single: Duration, parallel: Duration| {
            let mrays = |d: Duration| rays as f64 / d.as_secs_f64().max(1e-9) / 1e6;
            let mut row = head.clone();
            row.extend([
                set.to_string(),
                rays.to_string(),
                hits,
                format!("{:.2}", mrays(single)),
                format!("{:.2}", mrays(parallel)),
                format!(
                    "{:.2}",
                    single.as_secs_f64() / parallel.as_secs_f64().max(1e-12)
                ),
                threads.to_string(),
            ]);
            row
        };
        for s in &tree.sets {
            let hits = s.hits.to_string();
            rows.push(row(
                s.kind.name(),
                s.rays as u64,
                hits,
                s.single,
                s.parallel,
            ));
        }
        rows.push(row(
            "render",
            tree.render_rays,
            String::new(),
            tree.render_single,
            tree.render_parallel,
        ));
    }
    rows
}

/// One grid's results in words: sizes, builds, memory and each ray set's Mrays/s.
fn print_throughput(t: &Throughput, threads: usize) {
    let tris = t.triangles as f64;
    outln!(
        "  G={} S={}: {} triangles, primitive records {:.1} B/triangle (mesh buffers {:.1} \
         more); median split build {:.1} ms",
        t.g,
        t.s,
        t.triangles,
        t.primitive_bytes as f64 / tris,
        t.mesh_bytes as f64 / tris,
        ms(t.build_median_split),
    );
    for tree in &t.trees {
        outln!(
            "  {} ({}): build {:.1} ms; {} nodes, depth {}; memory {:.1} B/triangle = tree {:.1} \
             (nodes {:.1}, leaves {:.1}) + primitive records {:.1}",
            tree.kind.name(),
            tree.isa,
            ms(tree.build),
            tree.nodes,
            tree.depth,
            (tree.accel_bytes + t.primitive_bytes) as f64 / tris,
            tree.accel_bytes as f64 / tris,
            (tree.accel_bytes - tree.leaf_bytes) as f64 / tris,
            tree.leaf_bytes as f64 / tris,
            t.primitive_bytes as f64 / tris,
        );
        for s in &tree.sets {
            outln!(
                "    {:<10} {:>7} rays: {:>7.2} Mrays/s on 1 thread, {:>7.2} on {threads}",
                s.kind.name(),
                s.rays,
                s.mrays(s.single),
                s.mrays(s.parallel)
            );
        }
    }
}
