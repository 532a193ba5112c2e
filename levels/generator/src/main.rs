//! `levelgen`: writes Headlamp's shipped levels procedurally: "The Cellar", "The Gallery" and
//! "The Hall".
//!
//! ```text
//! cargo run -p levelgen --release [-- [--map] [--only ID] [LEVELS_DIR]]
//! ```
//!
//! Writes each level into `LEVELS_DIR/ID` (default: the workspace's `levels/`): `scene.gltf`
//! (text glTF 2.0), `scene.bin` (its buffer), `level.toml`, and the PNG textures its materials
//! use. The output is byte-for-byte deterministic. `--only ID` writes one level (`cellar`,
//! `gallery` or `hall`); `--map` also prints a top-down ASCII map of each layout.

mod cellar;
mod gallery;
mod geometry;
mod gltf_writer;
mod hall;
mod layout;
#[cfg(test)]
mod layout_checks;
mod level_file;
mod map;
mod materials;
mod textures;

use geometry::MeshBuffers;
use layout::{Level, Shape};
use materials::Material;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const SCENE_FILE: &str = "scene.gltf";
const BIN_FILE: &str = "scene.bin";
const LEVEL_FILE: &str = "level.toml";

/// Every shipped level, the default one first.
pub fn all_levels() -> Vec<Level> {
    vec![cellar::cellar(), gallery::gallery(), hall::hall()]
}

/// The generated files' contents.
pub struct Outputs {
    pub gltf: String,
    pub bin: Vec<u8>,
    pub toml: String,
    /// The textures' file names and PNG bytes.
    pub textures: Vec<(String, Vec<u8>)>,
}

/// Merges all geometry of the level into one mesh per material, in `Material` order, with
/// texture coordinates scaled to each material's texture.
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
    for (material, mesh) in &mut meshes {
        if let Some((_, metres)) = material.texture() {
            mesh.scale_uvs(metres);
        }
    }
    meshes
}

pub fn generate(level: &Level) -> Outputs {
    let meshes = build_meshes(level);
    let gltf = gltf_writer::write(level, &meshes, BIN_FILE);
    Outputs {
        gltf: gltf.json,
        bin: gltf.bin,
        toml: level_file::level_toml(level, SCENE_FILE),
        textures: gltf.textures.iter().map(|t| (t.file_name(), t.png())).collect(),
    }
}

fn default_levels_dir() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = manifest.ancestors().nth(2).unwrap_or(manifest);
    root.join("levels")
}

fn write_outputs(dir: &Path, out: &Outputs) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    std::fs::write(dir.join(SCENE_FILE), &out.gltf)?;
    std::fs::write(dir.join(BIN_FILE), &out.bin)?;
    std::fs::write(dir.join(LEVEL_FILE), &out.toml)?;
    for (name, png) in &out.textures {
        std::fs::write(dir.join(name), png)?;
    }
    Ok(())
}

fn main() -> ExitCode {
    let mut show_map = false;
    let mut only = None;
    let mut dir = None;
    let ids: Vec<&str> = all_levels().iter().map(|l| l.id).collect();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--map" => show_map = true,
            "--only" => match args.next() {
                Some(id) if ids.contains(&id.as_str()) => only = Some(id),
                other => {
                    eprintln!("levelgen: --only needs one of {} (got {other:?})", ids.join(", "));
                    return ExitCode::FAILURE;
                }
            },
            "-h" | "--help" => {
                println!(
                    "usage: levelgen [--map] [--only ID] [LEVELS_DIR]\n\
                     Writes each shipped level ({}) into LEVELS_DIR/ID: {SCENE_FILE}, {BIN_FILE}, {LEVEL_FILE}\n\
                     and its PNG textures (default LEVELS_DIR: {}). --only ID writes one level;\n\
                     --map prints a top-down ASCII map of each.",
                    ids.join(", "),
                    default_levels_dir().display()
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
    let root = dir.unwrap_or_else(default_levels_dir);

    for level in all_levels().into_iter().filter(|l| only.as_deref().is_none_or(|id| id == l.id)) {
        let dir = root.join(level.id);
        let out = generate(&level);
        if let Err(e) = write_outputs(&dir, &out) {
            eprintln!("levelgen: writing {}: {e}", dir.display());
            return ExitCode::FAILURE;
        }
        let meshes = build_meshes(&level);
        let triangles: usize = meshes.iter().map(|(_, m)| m.indices.len() / 3).sum();
        let vertices: usize = meshes.iter().map(|(_, m)| m.vertex_count()).sum();
        let png_bytes: usize = out.textures.iter().map(|(_, png)| png.len()).sum();
        println!(
            "levelgen: wrote \"{}\" to {}: {} rooms, {} doorways, {} boxes + {} ramp(s), {} meshes, {vertices} vertices, {triangles} triangles, {} bytes of buffer, {} textures ({png_bytes} bytes)",
            level.name,
            dir.display(),
            level.rooms.len(),
            level.doorways.len(),
            level.solids().len(),
            level.props.iter().filter(|p| matches!(p.shape, Shape::Ramp { .. })).count(),
            meshes.len(),
            out.bin.len(),
            out.textures.len(),
        );
        if show_map {
            print!("{}", map::ascii_map(&level, &level.solids()));
        }
    }
    ExitCode::SUCCESS
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_is_deterministic() {
        for (a, b) in all_levels().iter().zip(all_levels()) {
            let (a, b) = (generate(a), generate(&b));
            assert_eq!(a.gltf, b.gltf);
            assert_eq!(a.bin, b.bin);
            assert_eq!(a.toml, b.toml);
            assert_eq!(a.textures, b.textures);
            assert!(!a.bin.is_empty());
        }
    }

    #[test]
    fn writes_its_files_and_rewrites_identically() {
        for level in all_levels() {
            let dir = std::env::temp_dir().join(format!("levelgen-test-{}-{}", std::process::id(), level.id));
            let out = generate(&level);
            write_outputs(&dir, &out).unwrap();
            let mut files = vec![SCENE_FILE.to_string(), BIN_FILE.to_string(), LEVEL_FILE.to_string()];
            files.extend(out.textures.iter().map(|(name, _)| name.clone()));
            let first: Vec<Vec<u8>> = files.iter().map(|f| std::fs::read(dir.join(f)).unwrap()).collect();
            write_outputs(&dir, &generate(&level)).unwrap();
            for (f, bytes) in files.iter().zip(&first) {
                assert_eq!(&std::fs::read(dir.join(f)).unwrap(), bytes, "{f} changed");
            }
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }

    /// A level folder stays small enough to ship in the repository (well under 2 MB).
    #[test]
    fn level_folders_are_small() {
        for level in all_levels() {
            let out = generate(&level);
            let bytes = out.gltf.len() + out.bin.len() + out.toml.len();
            let bytes = bytes + out.textures.iter().map(|(_, png)| png.len()).sum::<usize>();
            assert!(bytes < 1024 * 1024, "{}: {bytes} bytes", level.id);
        }
    }

    #[test]
    fn level_ids_are_distinct_folder_names() {
        let levels = all_levels();
        assert_eq!(levels[0].id, "cellar", "the default level comes first");
        for (i, a) in levels.iter().enumerate() {
            assert!(a.id.chars().all(|c| c.is_ascii_lowercase() || c == '_'), "{}", a.id);
            assert!(levels[i + 1..].iter().all(|b| b.id != a.id && b.name != a.name));
        }
    }

    #[test]
    fn one_mesh_per_material_and_24_vertices_per_box() {
        for level in all_levels() {
            one_mesh_per_material(&level);
        }
    }

    fn one_mesh_per_material(level: &Level) {
        let meshes = build_meshes(level);
        let mut materials: Vec<Material> = meshes.iter().map(|(m, _)| *m).collect();
        materials.dedup();
        assert_eq!(materials.len(), meshes.len());
        let boxes = level.solids().len();
        let ramps = level.props.iter().filter(|p| matches!(p.shape, Shape::Ramp { .. })).count();
        let vertices: usize = meshes.iter().map(|(_, m)| m.vertex_count()).sum();
        assert_eq!(vertices, 24 * boxes + 18 * ramps);
    }

    #[test]
    fn default_levels_dir_is_in_the_workspace() {
        let d = default_levels_dir();
        assert!(d.ends_with("levels"));
        assert!(d.join("generator").join("Cargo.toml").exists());
    }
}
