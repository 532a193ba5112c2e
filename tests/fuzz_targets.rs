//! Fuzz targets: what a user can hand Headlamp as a file, fed arbitrary bytes. Each target
//! must return (an `Ok` or an `Err`, never a panic, never an endless wait) for any input.
//!
//! Two drivers share these entry points: `tests/fuzz_corpus.rs` mutates a seed corpus of the
//! shipped files for a bounded number of rounds in the test command, and the cargo-fuzz
//! project in `tests/fuzz/` (libFuzzer, nightly) runs them for as long as you like
//! (docs/testing.md says how).

use std::path::{Path, PathBuf};

use engine::replay::Replay;
use engine::scene;

/// What is fuzzed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A .gltf (JSON), its buffers and images embedded or beside it.
    Gltf,
    /// A .glb container.
    Glb,
    /// An .obj, with a valid .mtl beside it.
    Obj,
    /// An .mtl, named by a valid .obj.
    Mtl,
    /// A level folder's level.toml, with a valid scene beside it.
    LevelToml,
    /// A .replay file.
    Replay,
    /// An input script.
    Script,
    /// The player's config.toml.
    Config,
}

impl Target {
    pub const ALL: [Target; 8] = [
        Target::Gltf,
        Target::Glb,
        Target::Obj,
        Target::Mtl,
        Target::LevelToml,
        Target::Replay,
        Target::Script,
        Target::Config,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Target::Gltf => "gltf",
            Target::Glb => "glb",
            Target::Obj => "obj",
            Target::Mtl => "mtl",
            Target::LevelToml => "level_toml",
            Target::Replay => "replay",
            Target::Script => "script",
            Target::Config => "config",
        }
    }
}

/// A scratch folder per thread (libFuzzer may run several), where file-based loaders read.
fn scratch() -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("headlamp-fuzz-{}-{:?}", std::process::id(), std::thread::current().id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    dir
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write a fuzz input");
    path
}

const OBJ: &[u8] = b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nusemtl a\nf 1/1/1 2/1/1 3/1/1\n";
const MTL: &[u8] = b"newmtl a\nKd 0.8 0.2 0.1\nKe 0 0 0\n";

/// Feeds `data` to `target`'s reader: Ok when it was accepted (most mutated inputs are not),
/// else the reader's error. Panics only where the reader does, which is what the drivers look
/// for.
pub fn run(target: Target, data: &[u8]) -> Result<(), String> {
    let dir = scratch();
    let text = || String::from_utf8_lossy(data).into_owned();
    match target {
        Target::Gltf => scene::load_gltf(&write(&dir, "f.gltf", data)).map(drop).map_err(|e| e.to_string()),
        Target::Glb => scene::load_gltf(&write(&dir, "f.glb", data)).map(drop).map_err(|e| e.to_string()),
        Target::Obj => {
            write(&dir, "m.mtl", MTL);
            scene::load_obj(&write(&dir, "f.obj", data)).map(drop).map_err(|e| e.to_string())
        }
        Target::Mtl => {
            if !dir.join("t.png").exists() {
                image::RgbaImage::new(1, 1).save(dir.join("t.png")).expect("a texture for map_Kd");
            }
            write(&dir, "m.mtl", data);
            scene::load_obj(&write(&dir, "f.obj", OBJ)).map(drop).map_err(|e| e.to_string())
        }
        Target::LevelToml => {
            let level = dir.join("level");
            std::fs::create_dir_all(&level).expect("a level folder");
            write(&level, "scene.obj", OBJ);
            write(&level, "m.mtl", MTL);
            write(&level, "level.toml", data);
            scene::load_level(&level).map(drop).map_err(|e| e.to_string())
        }
        Target::Replay => Replay::parse(data, Path::new("f.replay")).map(drop).map_err(|e| e.to_string()),
        Target::Script => game::script::parse_steps(&text(), Path::new("f.txt")).map(drop),
        Target::Config => {
            game_ui::Config::from_toml(&text(), Path::new("config.toml")).map(drop).map_err(|e| e.to_string())
        }
    }
}

/// The seed corpus: the shipped files of each kind (and a config the game writes).
pub fn seeds(target: Target) -> Vec<Vec<u8>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let read = |p: PathBuf| std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    let levels: Vec<PathBuf> = ["cellar", "gallery", "hall"].iter().map(|l| root.join("levels").join(l)).collect();
    let in_dir = |dir: PathBuf, ext: &str| -> Vec<Vec<u8>> {
        let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == ext))
            .collect();
        files.sort();
        files.into_iter().map(read).collect()
    };
    match target {
        // The level's buffer and textures are files beside it; embedded, the seed stands alone.
        Target::Gltf => levels.iter().map(|l| embedded(l, false)).collect(),
        Target::Glb => levels.iter().map(|l| embedded(l, true)).collect(),
        Target::Obj => vec![OBJ.to_vec(), b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf -1 -2 -3\n".to_vec()],
        Target::Mtl => vec![MTL.to_vec(), b"newmtl a\nKd 1 1 1\nmap_Kd -s 1 1 1 t.png\nd 0.5\n".to_vec()],
        // Pointed at the small OBJ the target writes beside it.
        Target::LevelToml => levels
            .iter()
            .map(|l| {
                String::from_utf8_lossy(&read(l.join("level.toml")))
                    .replace("\"scene.gltf\"", "\"scene.obj\"")
                    .into_bytes()
            })
            .collect(),
        Target::Replay => in_dir(root.join("tests/replays"), "replay"),
        Target::Script => in_dir(root.join("tests/replays"), "txt"),
        Target::Config => vec![game_ui::Config::default().to_toml().into_bytes()],
    }
}

/// A level's scene.gltf with every file it names embedded: as data: URIs, or (`glb`) the
/// buffer in a GLB's BIN chunk and the images as data: URIs.
fn embedded(level: &Path, glb: bool) -> Vec<u8> {
    let read =
        |name: &str| std::fs::read(level.join(name)).unwrap_or_else(|e| panic!("{}/{name}: {e}", level.display()));
    let mut doc: serde_json::Value = serde_json::from_slice(&read("scene.gltf")).expect("a shipped glTF is JSON");
    let data_uri = |bytes: &[u8]| {
        serde_json::Value::String(format!("data:application/octet-stream;base64,{}", scene::encode_base64(bytes)))
    };
    // (`get_mut`: indexing a missing key would insert a null, which is not glTF.)
    for image in doc.get_mut("images").and_then(|i| i.as_array_mut()).into_iter().flatten() {
        let file = image["uri"].as_str().map(str::to_owned);
        if let Some(file) = file {
            image["uri"] =
                serde_json::Value::String(format!("data:image/png;base64,{}", scene::encode_base64(&read(&file))));
        }
    }
    let buffer = &mut doc["buffers"][0];
    let bin = read(buffer["uri"].as_str().expect("a shipped glTF names its buffer"));
    if !glb {
        buffer["uri"] = data_uri(&bin);
        return serde_json::to_vec(&doc).expect("JSON");
    }
    buffer.as_object_mut().expect("a buffer object").remove("uri");
    scene::pack_glb(&serde_json::to_vec(&doc).expect("JSON"), &bin)
}

/// A deterministic mutator (xorshift): the corpus driver's stand-in for libFuzzer's.
pub struct Mutator(u64);

impl Mutator {
    pub fn new(seed: u64) -> Self {
        Self(seed.max(1))
    }

    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    /// One to four edits of `input`: flipped bits, overwritten or deleted bytes, a repeated
    /// slice, a cut, or a number swapped for an edge value.
    pub fn mutate(&mut self, input: &[u8]) -> Vec<u8> {
        const NUMBERS: [&[u8]; 9] =
            [b"0", b"-1", b"4294967295", b"1e39", b"NaN", b"-0", b"65536", b"3.4e38", b"99999999999"];
        let mut out = input.to_vec();
        for _ in 0..1 + self.below(4) {
            let len = out.len();
            let at = self.below(len + 1);
            match self.below(6) {
                0 if len > 0 => out[at.min(len - 1)] ^= 1 << self.below(8),
                1 if len > 0 => out[at.min(len - 1)] = self.next() as u8,
                2 if len > 0 => {
                    let end = (at + 1 + self.below(64)).min(len);
                    out.drain(at.min(end)..end);
                }
                3 if len > 0 => {
                    let end = (at + 1 + self.below(256)).min(len);
                    let slice = out[at.min(end)..end].to_vec();
                    let to = self.below(out.len() + 1);
                    out.splice(to..to, slice);
                }
                4 => out.truncate(at),
                _ => {
                    // A digit run replaced by an edge number: sizes, counts, indices.
                    if let Some(start) = (at..len).find(|&i| out[i].is_ascii_digit()) {
                        let end = (start..len).find(|&i| !out[i].is_ascii_digit()).unwrap_or(len);
                        let number = NUMBERS[self.below(NUMBERS.len())];
                        out.splice(start..end, number.iter().copied());
                    }
                }
            }
        }
        out
    }
}
