//! Every bind group a shader declares, reflected with naga and compared with the Rust list that
//! makes its layout (`engine::bindings::Group`): each `@binding` in order with its `var`'s name
//! and kind, nothing more and nothing less, and each binding read by at least one entry point
//! that uses the group. Shared by engine/tests/bindings.rs and plugin_gi/tests/bindings.rs.
#![allow(dead_code)] // Each test uses part of it.

use std::collections::BTreeMap;

use engine::bindings::{BindingKind, WgslGroup};
use engine::wgpu::TextureFormat;

/// What naga says a global is, in [`BindingKind`]'s words; `texture_2d<f32>` may be read either way.
fn kinds_of(module: &naga::Module, var: &naga::GlobalVariable) -> Result<Vec<BindingKind>, String> {
    use naga::{AddressSpace, ImageClass, ScalarKind, StorageAccess, TypeInner};
    match (var.space, &module.types[var.ty].inner) {
        (AddressSpace::Uniform, _) => Ok(vec![BindingKind::Uniform]),
        (AddressSpace::Storage { access }, _) => {
            Ok(vec![BindingKind::Storage { read_only: !access.contains(StorageAccess::STORE) }])
        }
        (AddressSpace::Handle, TypeInner::Sampler { comparison }) => {
            Ok(vec![if *comparison { BindingKind::ComparisonSampler } else { BindingKind::Sampler }])
        }
        (AddressSpace::Handle, TypeInner::Image { dim: naga::ImageDimension::D2, arrayed: false, class }) => {
            match class {
                ImageClass::Sampled { kind: ScalarKind::Float, multi: false } => {
                    Ok(vec![BindingKind::Texture, BindingKind::FilteredTexture])
                }
                ImageClass::Sampled { kind: ScalarKind::Uint, multi: false } => Ok(vec![BindingKind::UintTexture]),
                ImageClass::Depth { multi: false } => Ok(vec![BindingKind::DepthTexture]),
                ImageClass::Storage { format, .. } => Ok(vec![BindingKind::StorageTexture(texture_format(*format)?)]),
                other => Err(format!("an image of class {other:?}, which no BindingKind describes")),
            }
        }
        (space, inner) => Err(format!("a {space:?} {inner:?}, which no BindingKind describes")),
    }
}

fn texture_format(format: naga::StorageFormat) -> Result<TextureFormat, String> {
    use naga::StorageFormat as S;
    Ok(match format {
        S::Rgba32Float => TextureFormat::Rgba32Float,
        S::Rgba16Float => TextureFormat::Rgba16Float,
        S::R32Float => TextureFormat::R32Float,
        S::Rgba32Uint => TextureFormat::Rgba32Uint,
        S::R32Uint => TextureFormat::R32Uint,
        S::Rgba8Unorm => TextureFormat::Rgba8Unorm,
        other => return Err(format!("storage format {other:?} is not in binding_check's table")),
    })
}

/// Checks `shaders` (name, source as written) against `declared`, their crate's groups, and
/// `borrowed`, another crate's that they include: every `@group` of every shader is described
/// by a [`WgslGroup`] (written for that shader, or for an include of it) and agrees with it;
/// each of `declared` is declared somewhere and each of its bindings read. Returns the
/// problems, each naming shader, group and binding.
pub fn check(
    shaders: &[(&str, &str)],
    includes: &[(&str, &str)],
    declared: &[WgslGroup],
    borrowed: &[WgslGroup],
) -> Vec<String> {
    let all: Vec<WgslGroup> = declared.iter().chain(borrowed).copied().collect();
    let mut problems = Vec::new();
    // Per list (file, group, label), the bindings some entry point that uses the group reads.
    let mut read: BTreeMap<(&str, u32, &str), Vec<bool>> = BTreeMap::new();
    for (name, source) in shaders {
        let composed = engine::shader::compose(source, includes);
        let module = match naga::front::wgsl::parse_str(&composed) {
            Ok(m) => m,
            Err(e) => {
                problems.push(format!("{name}: {}", e.emit_to_string(&composed)));
                continue;
            }
        };
        let info = naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
            .validate(&module);
        let info = match info {
            Ok(i) => i,
            Err(e) => {
                problems.push(format!("{name}: {}", e.emit_to_string(&composed)));
                continue;
            }
        };
        let own = engine::shader::included(source, includes);
        let mut groups: BTreeMap<u32, Vec<(u32, naga::Handle<naga::GlobalVariable>)>> = BTreeMap::new();
        for (handle, var) in module.global_variables.iter() {
            if let Some(b) = &var.binding {
                groups.entry(b.group).or_default().push((b.binding, handle));
            }
        }
        for (group, mut vars) in groups {
            vars.sort();
            let candidates: Vec<&WgslGroup> =
                all.iter().filter(|d| d.group == group && (d.shader == *name || own.contains(&d.shader))).collect();
            if candidates.is_empty() {
                problems.push(format!("{name}: @group({group}) is described by no Rust list (bindings::WgslGroup)"));
                continue;
            }
            // Several lists may describe one group: layouts that differ only in how a texture
            // is read (filtered or loaded).
            for d in candidates {
                problems.extend(check_group(name, group, d, (&module, &info), &vars, &mut read));
            }
        }
    }
    for d in declared {
        if !read.contains_key(&(d.shader, d.group, d.layout.label)) {
            problems.push(format!(
                "{}: {} describes @group({}), which no shader declares",
                d.shader, d.layout.label, d.group
            ));
        }
        if let Some(used) = read.get(&(d.shader, d.group, d.layout.label)) {
            for (b, reads) in d.layout.bindings.iter().zip(used) {
                if !reads {
                    problems.push(format!(
                        "{}: @group({}) '{}' of {} is read by no entry point that uses the group",
                        d.shader, d.group, b.name, d.layout.label
                    ));
                }
            }
        }
    }
    problems
}

/// The problems of one group of shader `name` (its `vars` by binding) against its list `d`;
/// what its entry points read of it is added to `read`.
fn check_group<'d>(
    name: &str,
    group: u32,
    d: &'d WgslGroup,
    (module, info): (&naga::Module, &naga::valid::ModuleInfo),
    vars: &[(u32, naga::Handle<naga::GlobalVariable>)],
    read: &mut BTreeMap<(&'d str, u32, &'d str), Vec<bool>>,
) -> Vec<String> {
    let mut problems = Vec::new();
    let at = |i: usize| format!("{name}: @group({group}) @binding({i})");
    for (i, expected) in d.layout.bindings.iter().enumerate() {
        let Some((_, handle)) = vars.iter().find(|(b, _)| *b as usize == i) else {
            problems.push(format!("{}: '{}' of {} is not declared in WGSL", at(i), expected.name, d.layout.label));
            continue;
        };
        let var = &module.global_variables[*handle];
        let wgsl_name = var.name.as_deref().unwrap_or("");
        if wgsl_name != expected.name {
            problems.push(format!("{}: WGSL names it '{wgsl_name}', {} '{}'", at(i), d.layout.label, expected.name));
        }
        match kinds_of(module, var) {
            Ok(kinds) if kinds.contains(&expected.kind) => {}
            Ok(kinds) => problems.push(format!(
                "{}: '{wgsl_name}' is {:?} in WGSL, {:?} in {}",
                at(i),
                kinds[0],
                expected.kind,
                d.layout.label
            )),
            Err(e) => problems.push(format!("{}: '{wgsl_name}' is {e}", at(i))),
        }
    }
    // The entry points the layout serves: those listed, or every one that uses the group.
    let serves =
        |index: usize| d.entry_points.is_empty() || d.entry_points.contains(&module.entry_points[index].name.as_str());
    let read_by_served = |handle: naga::Handle<naga::GlobalVariable>| {
        (0..module.entry_points.len()).any(|i| serves(i) && !info.get_entry_point(i)[handle].is_empty())
    };
    for entry in d.entry_points {
        if !module.entry_points.iter().any(|e| e.name == *entry) {
            problems.push(format!("{name}: {} names entry point '{entry}', which it has not", d.layout.label));
        }
    }
    for (b, handle) in vars {
        // A layout for some entry points may stop short of bindings they leave unread.
        let theirs = d.entry_points.is_empty() || read_by_served(*handle);
        if *b as usize >= d.layout.bindings.len() && theirs {
            let wgsl_name = module.global_variables[*handle].name.as_deref().unwrap_or("");
            problems.push(format!("{}: '{wgsl_name}' is not in {}", at(*b as usize), d.layout.label));
        }
    }
    // The entry points that use the group at all, and what they read of it.
    let used = read.entry((d.shader, d.group, d.layout.label)).or_insert_with(|| vec![false; d.layout.bindings.len()]);
    for index in (0..module.entry_points.len()).filter(|i| serves(*i)) {
        let function = info.get_entry_point(index);
        let uses: Vec<bool> = vars.iter().map(|(_, h)| !function[*h].is_empty()).collect();
        if !uses.iter().any(|u| *u) {
            continue;
        }
        for ((b, _), reads) in vars.iter().zip(uses) {
            if let Some(slot) = used.get_mut(*b as usize) {
                *slot |= reads;
            }
        }
    }
    problems
}
