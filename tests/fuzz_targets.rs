//! Fuzz targets: what a user can hand Headlamp as a file, fed arbitrary bytes. Each target
//! must return (an `Ok` or an `Err`, never a panic, never an endless wait) for any input.
//!
//! Two drivers share these entry points: `tests/fuzz_corpus.rs` mutates a seed corpus of the
//! shipped files for a bounded number of rounds in the test command, each input under a time
//! and memory limit (`fuzz_bounds.rs`), and the cargo-fuzz project in `tests/fuzz/` (libFuzzer,
//! nightly) runs them for as long as you like (docs/testing.md says how).
//!
//! The corpus driver's mutations know the files' structure where bytes alone would stop at the
//! surface: a glTF's binary buffer and images are mutated before they are base64-encoded (else
//! nearly every edit lands in base64 text) and its JSON apart from them, and a replay's body is
//! re-sealed with its checksum after a mutation (else nearly every edit stops at the checksum).

use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

use engine::replay::Replay;
use engine::scene;
use game::sim::{LevelWorld, Simulation};

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
        Target::Replay => replay(data),
        Target::Script => game::script::parse_steps(&text(), Path::new("f.txt")).map(drop),
        Target::Config => {
            game_ui::Config::from_toml(&text(), Path::new("config.toml")).map(drop).map_err(|e| e.to_string())
        }
    }
}

/// Ticks of a fuzzed replay that are simulated: enough for its commands to move, turn, jump,
/// fire and throw the lamp, few enough for thousands of inputs.
const SIMULATED_TICKS: usize = 32;

/// The shipped levels, which a fuzzed replay may name, with their worlds: loaded once.
fn shipped_levels() -> &'static [(String, scene::Level, Arc<LevelWorld>)] {
    static LEVELS: OnceLock<Vec<(String, scene::Level, Arc<LevelWorld>)>> = OnceLock::new();
    LEVELS.get_or_init(|| {
        SHIPPED_LEVELS
            .iter()
            .map(|id| {
                let level = scene::load_level(&root().join("levels").join(id)).expect("a shipped level");
                let world = game::sim::level_world(&level).expect("a shipped level's world");
                (id.to_string(), level, world)
            })
            .collect()
    })
}

/// Loads what `target` reads besides its input (the shipped levels a replay names), so that a
/// driver can do it before it starts counting an input's time and memory.
pub fn prepare(target: Target) {
    if target == Target::Replay {
        shipped_levels();
    }
}

const SHIPPED_LEVELS: [&str; 3] = ["cellar", "gallery", "hall"];

/// A replay as `headlamp replay` reads it: the container, the settings and commands decoded, and
/// when it names a shipped level, its first ticks simulated (a command is any 7 bytes, a tick
/// rate anything the header allows).
fn replay(data: &[u8]) -> Result<(), String> {
    let path = Path::new("f.replay");
    let replay = Replay::parse(data, path).map_err(|e| e.to_string())?;
    let (commands, _gi) = game::recording::decode(&replay, path).map_err(|e| format!("{e:#}"))?;
    let h = &replay.header;
    if let Some((_, level, world)) = shipped_levels().iter().find(|(id, ..)| *id == h.level_id) {
        let mut sim = Simulation::new(level, world.clone(), h.tick_rate, h.seed);
        for command in commands.iter().take(SIMULATED_TICKS) {
            sim.step(command);
        }
    }
    Ok(())
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A seed of the corpus, kept in the structure its mutations need.
pub enum Seed {
    /// Any other file: mutated as bytes.
    Bytes(Vec<u8>),
    /// A glTF document whose buffer and images are given apart: `doc`'s `uri`s hold the
    /// placeholders [`BUFFER_PLACEHOLDER`] and [`image_placeholder`], filled in with base64
    /// `data:` URIs when encoded (a GLB's buffer, with no uri, becomes its BIN chunk).
    Gltf { doc: String, bin: Vec<u8>, images: Vec<Vec<u8>>, glb: bool },
    /// A replay's bytes before its checksum, sealed when encoded.
    Replay(Vec<u8>),
}

const BUFFER_PLACEHOLDER: &str = "@BUFFER@";

fn image_placeholder(i: usize) -> String {
    format!("@IMAGE{i}@")
}

impl Seed {
    /// The file this seed stands for.
    pub fn encode(&self) -> Vec<u8> {
        match self {
            Seed::Bytes(bytes) => bytes.clone(),
            Seed::Gltf { doc, bin, images, glb } => encode_gltf(doc, bin, images, *glb),
            Seed::Replay(body) => seal(body.clone()),
        }
    }
}

fn encode_gltf(doc: &str, bin: &[u8], images: &[Vec<u8>], glb: bool) -> Vec<u8> {
    let mut doc = doc.to_string();
    for (i, image) in images.iter().enumerate() {
        doc = doc.replace(&image_placeholder(i), &format!("data:image/png;base64,{}", scene::encode_base64(image)));
    }
    if glb {
        return scene::pack_glb(doc.as_bytes(), bin);
    }
    let uri = format!("data:application/octet-stream;base64,{}", scene::encode_base64(bin));
    doc.replace(BUFFER_PLACEHOLDER, &uri).into_bytes()
}

/// A replay's body followed by its checksum, as `ReplayWriter` writes it.
fn seal(mut body: Vec<u8>) -> Vec<u8> {
    let sum = engine::replay::checksum(&body);
    body.extend_from_slice(&sum.to_le_bytes());
    body
}

/// The seed corpus: the shipped files of each kind (and a config the game writes).
pub fn seeds(target: Target) -> Vec<Seed> {
    let bytes = |files: Vec<Vec<u8>>| files.into_iter().map(Seed::Bytes).collect();
    match target {
        Target::Gltf | Target::Glb => {
            let glb = target == Target::Glb;
            SHIPPED_LEVELS.iter().map(|l| split_gltf(&root().join("levels").join(l), glb)).collect()
        }
        Target::Replay => seed_files(target)
            .into_iter()
            .map(|file| Seed::Replay(file[..file.len().saturating_sub(8)].to_vec()))
            .collect(),
        _ => bytes(seed_files(target)),
    }
}

/// The seed corpus as files, for cargo-fuzz's starting corpus.
pub fn seed_files(target: Target) -> Vec<Vec<u8>> {
    let root = root();
    let read = |p: PathBuf| std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    let levels: Vec<PathBuf> = SHIPPED_LEVELS.iter().map(|l| root.join("levels").join(l)).collect();
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
        Target::Gltf | Target::Glb => seeds(target).iter().map(Seed::encode).collect(),
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

/// A level's scene.gltf with the files it names read: its buffer and images apart from the
/// document, which names them by placeholders.
fn split_gltf(level: &Path, glb: bool) -> Seed {
    let read =
        |name: &str| std::fs::read(level.join(name)).unwrap_or_else(|e| panic!("{}/{name}: {e}", level.display()));
    let mut doc: serde_json::Value = serde_json::from_slice(&read("scene.gltf")).expect("a shipped glTF is JSON");
    let mut images = Vec::new();
    // (`get_mut`: indexing a missing key would insert a null, which is not glTF.)
    for image in doc.get_mut("images").and_then(|i| i.as_array_mut()).into_iter().flatten() {
        let file = image["uri"].as_str().map(str::to_owned);
        if let Some(file) = file {
            image["uri"] = image_placeholder(images.len()).into();
            images.push(read(&file));
        }
    }
    let buffer = &mut doc["buffers"][0];
    let bin = read(buffer["uri"].as_str().expect("a shipped glTF names its buffer"));
    if glb {
        // A GLB's buffer is its BIN chunk: the buffer without a uri.
        buffer.as_object_mut().expect("a buffer object").remove("uri");
    } else {
        buffer["uri"] = BUFFER_PLACEHOLDER.into();
    }
    Seed::Gltf { doc: serde_json::to_string(&doc).expect("JSON"), bin, images, glb }
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

    /// An input made from `seed`: a quarter of the time its file's bytes mutated, else a part
    /// of its structure (a glTF's JSON, buffer or an image; a replay's body, re-sealed).
    pub fn mutate_seed(&mut self, seed: &Seed) -> Vec<u8> {
        if self.below(4) == 0 {
            return self.mutate(&seed.encode());
        }
        match seed {
            Seed::Bytes(bytes) => self.mutate(bytes),
            Seed::Gltf { doc, bin, images, glb } => match self.below(2 + !images.is_empty() as usize) {
                0 => encode_gltf(&String::from_utf8_lossy(&self.mutate(doc.as_bytes())), bin, images, *glb),
                1 => encode_gltf(doc, &self.mutate(bin), images, *glb),
                _ => {
                    let mut images = images.clone();
                    let i = self.below(images.len());
                    images[i] = self.mutate(&images[i]);
                    encode_gltf(doc, bin, &images, *glb)
                }
            },
            Seed::Replay(body) => seal(self.mutate(body)),
        }
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
