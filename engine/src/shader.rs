//! WGSL sources, compiled into the binary, with a minimal `#include "file.wgsl"` so passes
//! share declarations without a shader preprocessor dependency.

/// The engine's shared include files, by the name used in `#include`.
pub const ENGINE_INCLUDES: &[(&str, &str)] = &[
    ("common.wgsl", include_str!("../../shaders/common.wgsl")),
    ("scene_surface.wgsl", include_str!("../../shaders/scene_surface.wgsl")),
    ("lights.wgsl", include_str!("../../shaders/lights.wgsl")),
    ("brdf.wgsl", include_str!("../../shaders/brdf.wgsl")),
];

/// Replaces each `#include "name"` line with the named source (engine includes first, then
/// `extra`); each file is included once. Unknown names are a programming error.
pub fn compose(source: &str, extra: &[(&str, &str)]) -> String {
    let mut out = String::new();
    let mut included: Vec<&str> = Vec::new();
    expand(source, extra, &mut included, &mut out);
    out
}

/// The names of the files `source` includes, directly or through another include, as
/// [`compose`] expands them.
pub fn included<'a>(source: &'a str, extra: &[(&'a str, &'a str)]) -> Vec<&'a str> {
    let mut included = Vec::new();
    expand(source, extra, &mut included, &mut String::new());
    included
}

fn expand<'a>(source: &'a str, extra: &[(&'a str, &'a str)], included: &mut Vec<&'a str>, out: &mut String) {
    for line in source.lines() {
        let Some(rest) = line.trim().strip_prefix("#include") else {
            out.push_str(line);
            out.push('\n');
            continue;
        };
        let name = rest.trim().trim_matches('"');
        if included.contains(&name) {
            continue;
        }
        let (name, text) = ENGINE_INCLUDES
            .iter()
            .chain(extra.iter())
            .find(|(n, _)| *n == name)
            .copied()
            .unwrap_or_else(|| panic!("shader include '{name}' is not registered"));
        included.push(name);
        expand(text, extra, included, out);
    }
}

/// Builds a shader module from a WGSL pass file.
pub fn module(device: &wgpu::Device, label: &str, source: &str, extra: &[(&str, &str)]) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(compose(source, extra).into()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn include_is_expanded_once() {
        let extra = [("a.wgsl", "const A: f32 = 1.0;"), ("b.wgsl", "#include \"a.wgsl\"\nconst B: f32 = A;")];
        let out = compose("#include \"a.wgsl\"\n#include \"b.wgsl\"\nfn f() {}", &extra);
        assert_eq!(out.matches("const A").count(), 1);
        assert!(out.contains("const B"));
        assert_eq!(included("#include \"b.wgsl\"\nfn f() {}", &extra), ["b.wgsl", "a.wgsl"]);
        assert!(out.ends_with("fn f() {}\n"));
    }

    #[test]
    fn every_engine_shader_parses_after_composition() {
        for (name, src) in crate::passes::SHADERS {
            let composed = compose(src, &[]);
            assert!(!composed.contains("#include"), "{name} still has an include");
        }
    }
}
