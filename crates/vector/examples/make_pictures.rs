//! Draws the pictures of `docs/vector.md`: visible regions and hidden-line
//! drawings of the spider, two intersecting planes, the cyclic bars and a
//! torus, and the painter's SVG of the spider beside the regions SVG.
//!
//! `cargo run --release -p hider-vector --example make_pictures [out_dir] [spider.obj]`
//! (defaults `docs/images` and `assets/spider/spider.obj`;
//! the spider is skipped when the file is not there).

use std::path::{Path, PathBuf};

use glam::DVec3;
use hider_geom::Camera;
use hider_painter::Painter;
use hider_scene::{
    Frame, Hider, Material, Mesh, PrepareOptions, Scene, ShadeMode, View, load_obj, prepare,
};
use hider_testkit::hard_cases;
use hider_vector::{
    SvgInfo, VectorOptions, hidden_lines_in, lines_document, regions_document, visible_regions,
    write_document, write_regions_svg,
};

/// Two unit squares crossing at right angles.
fn crossing_planes() -> Scene {
    let mut scene = Scene::default();
    let p = DVec3::new;
    let quads = [
        (
            "floor",
            [
                p(-1.0, 0.0, -1.0),
                p(1.0, 0.0, -1.0),
                p(1.0, 0.0, 1.0),
                p(-1.0, 0.0, 1.0),
            ],
            [0.85, 0.45, 0.2],
        ),
        (
            "wall",
            [
                p(-1.0, -1.0, 0.0),
                p(1.0, -1.0, 0.0),
                p(1.0, 1.0, 0.0),
                p(-1.0, 1.0, 0.0),
            ],
            [0.2, 0.45, 0.85],
        ),
    ];
    for (name, corners, colour) in quads {
        let mesh = Mesh {
            name: name.into(),
            positions: corners.to_vec(),
            indices: vec![[0, 1, 2], [0, 2, 3]],
            ..Mesh::default()
        };
        let material = Material {
            name: name.into(),
            diffuse: colour,
            ..Material::default()
        };
        scene.push_mesh(mesh, Some(material));
    }
    scene.camera = Some(Camera::perspective(
        p(2.0, 1.5, 3.5),
        DVec3::ZERO,
        0.5,
        50.0,
    ));
    scene
}

fn draw(
    dir: &Path,
    name: &str,
    scene: &Scene,
    size: u32,
    options: &VectorOptions,
) -> Result<(), hider_scene::Error> {
    let view = View::for_scene(scene, size, size)?;
    let s = prepare(scene, &view, &PrepareOptions::default())?;
    let info = SvgInfo::for_scene(scene, name, &s);
    let map = visible_regions(&s, options, ShadeMode::Lambert)?;
    let drawing = hidden_lines_in(&s, &map, options, &info.groups)?;
    let regions = dir.join(format!("vector-{name}-regions.svg"));
    let lines = dir.join(format!("vector-{name}-lines.svg"));
    write_document(&regions, &regions_document(&s, &map, options, &info))?;
    // Lines on paper: white behind them, so they show on a dark page too.
    let paper = options.clone().with_background(Some("white".into()));
    write_document(&lines, &lines_document(&s, &drawing, &paper, &info))?;
    println!(
        "{name}: {} paths ({}), {} polylines ({})",
        map.groups.len(),
        regions.display(),
        drawing.visible.len(),
        lines.display()
    );
    Ok(())
}

fn main() -> Result<(), hider_scene::Error> {
    let args: Vec<String> = std::env::args().collect();
    let dir = PathBuf::from(args.get(1).cloned().unwrap_or_else(|| "docs/images".into()));
    let spider = PathBuf::from(
        args.get(2)
            .cloned()
            .unwrap_or_else(|| "assets/spider/spider.obj".into()),
    );
    let options = VectorOptions::default();
    let dashed = VectorOptions::default().with_dashed_hidden(true);
    draw(&dir, "planes", &crossing_planes(), 320, &dashed)?;
    draw(&dir, "bars", &hard_cases::bar_cycle(1e-3), 320, &dashed)?;
    let mut torus = hard_cases::torus(48, 24, 1.0, 0.4);
    torus.camera = Some(Camera::perspective(
        DVec3::new(0.0, 2.2, 2.6),
        DVec3::ZERO,
        0.5,
        50.0,
    ));
    draw(&dir, "torus", &torus, 320, &dashed)?;
    if spider.exists() {
        let scene = load_obj(&spider)?;
        draw(&dir, "spider", &scene, 400, &options)?;
        // The painter's SVG of the same frame, for the side-by-side.
        let s = prepare(
            &scene,
            &View::for_scene(&scene, 400, 400)?,
            &PrepareOptions::default(),
        )?;
        let mut painter = Painter::default();
        painter.render(&s, &mut Frame::new(400, 400)?)?;
        let path = dir.join("vector-spider-painter.svg");
        painter
            .ordered_polygons()
            .expect("the painter writes SVG")
            .write_svg(&s, &path, ShadeMode::Lambert)?;
        println!("spider painter: {}", path.display());
        // The regions bare and with a 0.5-pixel seam stroke, for the
        // seams picture.
        for (width, file) in [
            (0.0, "vector-spider-regions-bare.svg"),
            (0.5, "vector-spider-regions-stroked.svg"),
        ] {
            let stroked = options.clone().with_seam_stroke(width);
            let map = visible_regions(&s, &stroked, ShadeMode::Lambert)?;
            let path = dir.join(file);
            write_regions_svg(&s, &map, &stroked, &path)?;
            println!("spider regions, seam stroke {width}: {}", path.display());
        }
    } else {
        println!("no spider at {}, skipped", spider.display());
    }
    Ok(())
}
