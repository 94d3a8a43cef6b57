//! `heightray render`: a scene (or a height map alone) to a PNG and statistics in the paper's
//! shape; with `--frames`, a flythrough's frames ([`super::render_frames`]); with `--tile` or
//! `--tiles`, a poster's tiles ([`super::render_tiles`]).

use super::{loading, render_frames, render_ortho, render_progress, render_tiles, RenderArgs};
use heightray::heightfield::store;
use heightray::output_file;
use heightray::render::animation::Animation;
use heightray::render::annotate::{Annotations, Marked, Sheet};
use heightray::render::effects::MOST_RAYS;
use heightray::render::sun_position::SunPosition;
use heightray::render::{
    Camera, Contours, Culling, Frame, Lighting, Renderer, Scene, SceneError, SceneFile, Shader,
    Window,
};
use heightray::traverse::prepare;
use heightray::{Arith, Method, Terrain};
use serde_json::json;
use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;

/// A scene loaded and its terrain built, with the command line's overrides: what every kind of
/// render starts from.
pub struct Setup {
    /// The scene's camera (world coordinates) at the image size asked for.
    pub camera: Camera,
    /// The scene's camera path, if it has one.
    pub animation: Option<Animation>,
    pub terrain: Terrain,
    pub lighting: Lighting,
    pub method: Method,
    pub arith: Arith,
    pub pool: rayon::ThreadPool,
    /// What is drawn over each picture.
    pub annotations: Annotations,
    /// Contour lines on the terrain.
    pub contours: Option<Contours>,
}

impl Setup {
    /// Loads the scene of `args`, builds its terrain and applies the overrides.
    pub fn new(args: &RenderArgs) -> anyhow::Result<Setup> {
        let start = Instant::now();
        let scene = loading::stage(&format!("loading {}", args.scene.display()), || {
            load_scene(args)
        })?;
        let read_time = start.elapsed();
        let method = args.method.unwrap_or(scene.method);
        let arith = args.arith.unwrap_or(scene.arith);
        let field = scene.field;
        let terrain = loading::stage("building acceleration data", || Terrain::new(field));
        loading::summary(&args.scene, &terrain, read_time);
        let pool = super::knobs::worker_pool(
            args.threads
                .or_else(|| terrain.field().is_mapped().then(store::threads)),
        )?;
        let mut lighting = scene.lighting;
        if let Some(samples) = args.samples {
            anyhow::ensure!(
                (1..=MOST_RAYS).contains(&samples),
                "--samples must be from 1 to {MOST_RAYS}, got {samples}"
            );
            lighting.effects.samples = samples;
        }
        lighting.effects.adaptive |= args.adaptive;
        Ok(Setup {
            camera: scene.camera,
            animation: scene.animation,
            terrain,
            lighting,
            method,
            arith,
            pool,
            annotations: scene.annotations,
            contours: scene.contours,
        })
    }

    /// The renderer of `camera` (in world coordinates) over the terrain.
    pub fn renderer(&self, camera: Camera) -> Renderer<'_> {
        let camera = camera.in_grid(self.terrain.world_from_grid());
        let shader = Shader::new(
            &self.terrain,
            self.lighting,
            self.method,
            Culling::default(),
        )
        .with_contours(self.contours, &camera);
        Renderer {
            shader,
            camera,
            arith: self.arith,
        }
    }

    /// Draws the scene's annotations into `pixels` (bytes or 16-bit words), `window` of the
    /// whole image of `camera` (in world coordinates).
    pub fn annotate<P: Marked>(
        &self,
        camera: Camera,
        pixels: &mut [P],
        window: Window,
    ) -> anyhow::Result<()> {
        let sheet = Sheet {
            terrain: &self.terrain,
            camera,
            ramp: self.lighting.ramp,
            method: self.method,
            arith: self.arith,
        };
        self.annotations
            .draw(&sheet, pixels, window)
            .map_err(anyhow::Error::msg)
    }
}

pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    render_ortho::check_tiff_options(args)?;
    if args.frames.is_some() {
        return render_frames::run(args);
    }
    if args.tile.is_some() || args.tiles.is_some() {
        return render_tiles::run(args);
    }
    if args.ortho.ortho {
        return render_ortho::run(args);
    }
    // Before any work: a render that fails to be written only at its end is time lost.
    output_file::check_image(&args.output).map_err(anyhow::Error::msg)?;
    if let Some(path) = &args.stats {
        output_file::check(path, "stats.json").map_err(anyhow::Error::msg)?;
    }
    let setup = Setup::new(args)?;
    let (terrain, method, arith, pool) = (&setup.terrain, setup.method, setup.arith, &setup.pool);
    let renderer = setup.renderer(setup.camera);
    let (width, height) = setup.camera.size();
    // A 16-bit TIFF is made from the linear colours, not from the bytes: the frame keeps
    // their words too.
    let words = render_ortho::sixteen_bits(args);
    let mut frame = match words {
        true => Frame::with_words(width, height),
        false => Frame::new(width, height),
    };
    // Built before the clock starts, so the render time is the render's alone.
    let build_ms = prepare(terrain, method).0.as_secs_f64() * 1e3;
    let start = Instant::now();
    match args.packets.as_str() {
        "on" => pool.install(|| renderer.render_in_packets(&mut frame)),
        _ => pool.install(|| render_progress::render_with_estimate(&renderer, &mut frame)),
    }
    let render_ms = start.elapsed().as_secs_f64() * 1e3;
    let whole = Window {
        x: 0,
        y: 0,
        width,
        height,
    };
    // Drawn over what is written: the words of a 16-bit TIFF, else the bytes.
    match words {
        true => setup.annotate(setup.camera, &mut frame.words, whole)?,
        false => setup.annotate(setup.camera, &mut frame.pixels, whole)?,
    }

    if render_ortho::is_tiff(&args.output) {
        render_ortho::save_tiff(args, &frame)?;
    } else {
        output_file::save_rgb(&args.output, &frame.pixels, (width, height))
            .map_err(anyhow::Error::msg)?;
    }
    let rays = frame.totals.primary_rays + frame.totals.shadow_rays + frame.totals.effects.rays();
    // (Before the table: a reader of the table that stops early loses none of the files.)
    if let Some(path) = &args.stats {
        // The sun as a compass bearing (0 north, 90 east) and elevation, in degrees.
        let sun = SunPosition::from_direction(renderer.shader.lighting.sun);
        let mut stats = json!({
            "sun": { "azimuth_deg": sun.azimuth_deg, "elevation_deg": sun.elevation_deg },
            "width": width, "height": height, "threads": pool.current_num_threads(),
            "method": method.to_string(), "arith": arith.to_string(),
            "build_ms": build_ms, "render_ms": render_ms,
            "rays_per_second": rays as f64 / (render_ms / 1e3),
        });
        if let (Some(object), serde_json::Value::Object(more)) =
            (stats.as_object_mut(), frame.totals.to_json())
        {
            object.extend(more);
        }
        output_file::write_bytes(
            path,
            (serde_json::to_string_pretty(&stats)? + "\n").as_bytes(),
        )
        .map_err(anyhow::Error::msg)?;
    }
    let label = args.scene.display().to_string();
    let out = &mut std::io::stdout().lock();
    write!(out, "{}", frame.totals.table(&label, build_ms, render_ms))?;
    writeln!(
        out,
        "{:.3} Mrays/s ({} threads, {method}, {arith})",
        rays as f64 / render_ms / 1e3,
        pool.current_num_threads()
    )?;
    loading::store_memory(terrain);
    Ok(ExitCode::SUCCESS)
}

/// The scene file named, or the scene of a height map alone; at `--size` if given.
fn load_scene(args: &RenderArgs) -> Result<Scene, SceneError> {
    let path = &args.scene;
    let mut file = if SceneFile::is_scene_path(path) {
        SceneFile::read(path)?
    } else {
        SceneFile::for_map(path)
    };
    file.size = args.size;
    Scene::from_file(&file, Scene::base(path), path)
}
