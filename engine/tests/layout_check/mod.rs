//! WGSL structs as naga lays them out, compared with their Rust twins (`engine::gpu_layout`).
//! Shared by engine/tests/gpu_layouts.rs and plugin_gi/tests/gpu_layouts.rs.
#![allow(dead_code)] // Each test uses part of it.

use std::collections::BTreeMap;
use std::fmt::Write;

use engine::gpu_layout::Layout;
use engine::wgpu::VertexFormat;

/// A WGSL struct as naga lays it out (the layout WGSL gives it in a host-shareable buffer).
#[derive(Clone, Debug, PartialEq)]
pub struct WgslStruct {
    pub name: String,
    pub size: usize,
    pub members: Vec<Member>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    pub name: String,
    pub offset: usize,
    pub size: usize,
    /// `@location`, for stage IO.
    pub location: Option<u32>,
    /// The vertex attribute format that feeds this type, where there is one.
    pub vertex_format: Option<VertexFormat>,
}

impl WgslStruct {
    pub fn member(&self, name: &str) -> &Member {
        self.members.iter().find(|m| m.name == name).unwrap_or_else(|| panic!("{} has no member {name}", self.name))
    }
}

/// Every struct an assembled WGSL source (includes expanded) declares.
pub fn wgsl_structs(file: &str, source: &str) -> Vec<WgslStruct> {
    let module =
        naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{file}: {}", e.emit_to_string(source)));
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap_or_else(|e| panic!("{file}: {e}"));
    let mut structs = Vec::new();
    for (handle, ty) in module.types.iter() {
        let (Some(name), naga::TypeInner::Struct { members, .. }) = (&ty.name, &ty.inner) else {
            continue;
        };
        // naga's own result types (`__modf_result_f32`, …) are not the shaders' declarations.
        if name.starts_with("__") {
            continue;
        }
        let members = members
            .iter()
            .map(|m| Member {
                name: m.name.clone().unwrap_or_default(),
                offset: m.offset as usize,
                size: layouter[m.ty].size as usize,
                location: match m.binding {
                    Some(naga::Binding::Location { location, .. }) => Some(location),
                    _ => None,
                },
                vertex_format: vertex_format(&module.types[m.ty].inner),
            })
            .collect();
        structs.push(WgslStruct { name: name.clone(), size: layouter[handle].size as usize, members });
    }
    structs
}

fn vertex_format(inner: &naga::TypeInner) -> Option<VertexFormat> {
    use naga::Scalar;
    use VertexFormat as F;
    let (scalar, n) = match *inner {
        naga::TypeInner::Scalar(s) => (s, 1),
        naga::TypeInner::Vector { size, scalar } => (scalar, size as usize),
        _ => return None,
    };
    let formats = match scalar {
        Scalar::F32 => [F::Float32, F::Float32x2, F::Float32x3, F::Float32x4],
        Scalar::U32 => [F::Uint32, F::Uint32x2, F::Uint32x3, F::Uint32x4],
        Scalar::I32 => [F::Sint32, F::Sint32x2, F::Sint32x3, F::Sint32x4],
        _ => return None,
    };
    Some(formats[n - 1])
}

/// `pad…` or `_pad…`: bytes that only fill alignment gaps, on either side.
pub fn is_pad(name: &str) -> bool {
    name.trim_start_matches('_').starts_with("pad")
}

/// Whether `rust` has the layout of `wgsl`: the same size, and every non-pad member at the
/// same offset with the same size under the same name. Rust pad fields then lie where WGSL has
/// only padding (implicit, or its own pad members). The error names the struct and each field
/// that differs, with its WGSL and Rust offsets.
pub fn compare(wgsl: &WgslStruct, rust: &Layout) -> Result<(), String> {
    let mut errors = Vec::new();
    let name = if wgsl.name == rust.rust { wgsl.name.clone() } else { format!("{} (Rust {})", wgsl.name, rust.rust) };
    for m in wgsl.members.iter().filter(|m| !is_pad(&m.name)) {
        match rust.fields.iter().find(|f| f.name == m.name) {
            None => errors.push(format!("{name}.{}: WGSL offset {} has no Rust field", m.name, m.offset)),
            Some(f) if f.offset != m.offset || f.size != m.size => errors.push(format!(
                "{name}.{}: WGSL offset {} (size {}), Rust offset {} (size {})",
                m.name, m.offset, m.size, f.offset, f.size
            )),
            Some(_) => {}
        }
    }
    for f in rust.fields.iter().filter(|f| !is_pad(f.name)) {
        if !wgsl.members.iter().any(|m| m.name == f.name) {
            errors.push(format!("{name}.{}: Rust offset {} has no WGSL member", f.name, f.offset));
        }
    }
    if wgsl.size != rust.size {
        errors.push(format!("{name}: WGSL size {}, Rust size {}", wgsl.size, rust.size));
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors.join("\n"))
    }
}

/// What [`check`] went through.
pub struct Checked {
    /// Every struct of the files, by name.
    pub structs: BTreeMap<String, WgslStruct>,
    /// Twins compared with their WGSL struct.
    pub twins: usize,
}

/// Checks every struct of `files` (name, assembled source): one of the same name in several
/// files must be the same everywhere, and each must have a twin in `twins` with its layout, or
/// be listed in `gpu_only`; no twin or list entry may name a struct none of the files declare.
pub fn check(files: &[(&str, String)], twins: &[Layout], gpu_only: &[(&str, &str)]) -> Result<Checked, String> {
    let mut errors = String::new();
    let mut structs: BTreeMap<String, (&str, WgslStruct)> = BTreeMap::new();
    for (file, source) in files {
        for s in wgsl_structs(file, source) {
            match structs.get(&s.name) {
                Some((first, seen)) if *seen != s => {
                    writeln!(errors, "struct {} differs between {first} ({seen:?}) and {file} ({s:?})", s.name)
                        .unwrap();
                }
                Some(_) => {}
                None => {
                    structs.insert(s.name.clone(), (file, s));
                }
            }
        }
    }
    let mut compared = 0;
    for (name, (file, s)) in &structs {
        let listed = gpu_only.iter().any(|(n, _)| n == name);
        let mut mirrors = twins.iter().filter(|t| t.wgsl == name).peekable();
        if listed && mirrors.peek().is_some() {
            writeln!(errors, "{name} ({file}) has a Rust twin and is listed as GPU-only").unwrap();
        } else if !listed && mirrors.peek().is_none() {
            writeln!(errors, "{name} ({file}) has no Rust twin and is not listed as GPU-only").unwrap();
        }
        for twin in mirrors {
            compared += 1;
            if let Err(e) = compare(s, twin) {
                writeln!(errors, "{e}").unwrap();
            }
        }
    }
    for t in twins.iter().filter(|t| !structs.contains_key(t.wgsl)) {
        writeln!(errors, "Rust {} mirrors {}, which no WGSL file declares", t.rust, t.wgsl).unwrap();
    }
    for (name, _) in gpu_only.iter().filter(|(n, _)| !structs.contains_key(*n)) {
        writeln!(errors, "GPU-only {name}: no WGSL file declares it").unwrap();
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    Ok(Checked { structs: structs.into_iter().map(|(name, (_, s))| (name, s)).collect(), twins: compared })
}
