//! `levelgen`: writes Headlamp's first shipped level, "The Cellar", procedurally.
//!
//! ```text
//! cargo run -p levelgen --release [-- [--map] [OUT_DIR]]
//! ```
//!
//! Writes `scene.gltf` (text glTF 2.0), `scene.bin` (its buffer) and `level.toml` into `OUT_DIR`
//! (default: `levels/cellar` in the workspace). The output is byte-for-byte deterministic.
//! `--map` also prints a top-down ASCII map of the layout.

mod geometry;
mod gltf_writer;
mod layout;
mod level_file;
mod map;

use geometry::{Material, MeshBuffers};
use layout::{Level, Shape};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const SCENE_FILE: &str = "scene.gltf";
const BIN_FILE: &str = "scene.bin";
const LEVEL_FILE: &str = "level.toml";

/// The generated files' contents.
pub struct Outputs {
    pub gltf: String,
    pub bin: Vec<u8>,
    pub toml: String,
}

/// Merges all geometry of the level into one mesh per material, in `Material` order.
pub fn build_meshes(level: &Level) -> Vec<(Material, MeshBuffers)> {
    let mut meshes: Vec<(Material, MeshBuffers)> = Material::ALL.iter().map(|&m| (m, MeshBuffers::default())).collect();
    for solid in level.solids() {
        meshes[solid.material as usize].1.add_box(&solid.bounds);
    }
    for prop in &level.props {
        if let Shape::Ramp { bounds, high } = &prop.shape {
            meshes[prop.material as usize].1.add_ramp(bounds, *high);
        }
    }
    meshes.retain(|(_, m)| !m.is_empty());
    meshes
}

pub fn generate(level: &Level) -> Outputs {
    let meshes = build_meshes(level);
    let gltf = gltf_writer::write(level, &meshes, BIN_FILE);
    Outputs { gltf: gltf.json, bin: gltf.bin, toml: level_file::level_toml(level, SCENE_FILE) }
}

fn default_out_dir() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = manifest.ancestors().nth(2).unwrap_or(manifest);
    root.join("levels").join("cellar")
}

fn write_outputs(dir: &Path, out: &Outputs) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    std::fs::write(dir.join(SCENE_FILE), &out.gltf)?;
    std::fs::write(dir.join(BIN_FILE), &out.bin)?;
    std::fs::write(dir.join(LEVEL_FILE), &out.toml)?;
    Ok(())
}

fn main() -> ExitCode {
    let mut show_map = false;
    let mut dir = None;
    for arg in std::env::args().skip(1) {
        match arg.as_str() {
            "--map" => show_map = true,
            "-h" | "--help" => {
                println!(
                    "usage: levelgen [--map] [OUT_DIR]\n\
                     Writes {SCENE_FILE}, {BIN_FILE} and {LEVEL_FILE} of \"The Cellar\" into OUT_DIR\n\
                     (default {}). --map prints a top-down ASCII map.",
                    default_out_dir().display()
                );
                return ExitCode::SUCCESS;
            }
            a if a.starts_with('-') => {
                eprintln!("levelgen: unknown option {a} (try --help)");
                return ExitCode::FAILURE;
            }
            a if dir.is_none() => dir = Some(PathBuf::from(a)),
            a => {
                eprintln!("levelgen: unexpected argument {a}");
                return ExitCode::FAILURE;
            }
        }
    }
    let dir = dir.unwrap_or_else(default_out_dir);

    let level = layout::cellar();
    let out = generate(&level);
    if let Err(e) = write_outputs(&dir, &out) {
        eprintln!("levelgen: writing {}: {e}", dir.display());
        return ExitCode::FAILURE;
    }
    let meshes = build_meshes(&level);
    let triangles: usize = meshes.iter().map(|(_, m)| m.indices.len() / 3).sum();
    let vertices: usize = meshes.iter().map(|(_, m)| m.vertex_count()).sum();
    println!(
        "levelgen: wrote \"{}\" to {}: {} rooms, {} doorways, {} boxes + {} ramp(s), {} meshes, {vertices} vertices, {triangles} triangles, {} bytes of buffer",
        level.name,
        dir.display(),
        level.rooms.len(),
        level.doorways.len(),
        level.solids().len(),
        level.props.iter().filter(|p| matches!(p.shape, Shape::Ramp { .. })).count(),
        meshes.len(),
        out.bin.len(),
    );
    if show_map {
        print!("{}", map::ascii_map(&level, &level.solids()));
    }
    ExitCode::SUCCESS
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_is_deterministic() {
        let a = generate(&layout::cellar());
        let b = generate(&layout::cellar());
        assert_eq!(a.gltf, b.gltf);
        assert_eq!(a.bin, b.bin);
        assert_eq!(a.toml, b.toml);
        assert!(!a.bin.is_empty());
    }

    #[test]
    fn writes_three_files_and_rewrites_identically() {
        let dir = std::env::temp_dir().join(format!("levelgen-test-{}", std::process::id()));
        let out = generate(&layout::cellar());
        write_outputs(&dir, &out).unwrap();
        let first: Vec<Vec<u8>> =
            [SCENE_FILE, BIN_FILE, LEVEL_FILE].iter().map(|f| std::fs::read(dir.join(f)).unwrap()).collect();
        write_outputs(&dir, &generate(&layout::cellar())).unwrap();
        for (f, bytes) in [SCENE_FILE, BIN_FILE, LEVEL_FILE].iter().zip(&first) {
            assert_eq!(&std::fs::read(dir.join(f)).unwrap(), bytes, "{f} changed");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn one_mesh_per_material_and_24_vertices_per_box() {
        let level = layout::cellar();
        let meshes = build_meshes(&level);
        let mut materials: Vec<Material> = meshes.iter().map(|(m, _)| *m).collect();
        materials.dedup();
        assert_eq!(materials.len(), meshes.len());
        let boxes = level.solids().len();
        let ramps = level.props.iter().filter(|p| matches!(p.shape, Shape::Ramp { .. })).count();
        let vertices: usize = meshes.iter().map(|(_, m)| m.vertex_count()).sum();
        assert_eq!(vertices, 24 * boxes + 18 * ramps);
    }

    #[test]
    fn default_out_dir_is_in_the_workspace() {
        let d = default_out_dir();
        assert!(d.ends_with("levels/cellar"));
        assert!(d.parent().unwrap().join("generator").join("Cargo.toml").exists());
    }
}
