//! Render graph: ordering from declarations, culling, build-time errors, and the descriptor-keyed
//! pool (reuse across frames, aliasing of disjoint lifetimes, re-creation on resize).

use engine::gpu::Gpu;
use engine::graph::{CompiledGraph, GraphError, PassContext, PassDecl, RenderGraph, RenderPass, TextureDesc};
use engine::wgpu::TextureFormat;

/// A pass that only declares; `run` is never reached by these tests.
struct Decl {
    name: &'static str,
    reads: Vec<&'static str>,
    creates: Vec<(&'static str, TextureDesc)>,
    writes: Vec<&'static str>,
}

fn pass(name: &'static str) -> Decl {
    Decl { name, reads: vec![], creates: vec![], writes: vec![] }
}

impl Decl {
    fn reads(mut self, r: &'static str) -> Self {
        self.reads.push(r);
        self
    }
    fn creates(mut self, r: &'static str) -> Self {
        self.creates.push((r, TextureDesc::target(TextureFormat::Rgba16Float)));
        self
    }
    fn creates_desc(mut self, r: &'static str, d: TextureDesc) -> Self {
        self.creates.push((r, d));
        self
    }
    fn writes(mut self, r: &'static str) -> Self {
        self.writes.push(r);
        self
    }
}

impl RenderPass for Decl {
    fn name(&self) -> &str {
        self.name
    }
    fn declare(&self, d: &mut PassDecl) {
        for r in &self.reads {
            d.read(r);
        }
        for (r, desc) in &self.creates {
            d.create_texture(r, *desc);
        }
        for w in &self.writes {
            d.write(w);
        }
    }
    fn run(&mut self, _ctx: &mut PassContext<'_>) {}
}

fn decls(passes: Vec<Decl>) -> Vec<(String, PassDecl)> {
    passes
        .into_iter()
        .map(|p| {
            let mut d = PassDecl::default();
            p.declare(&mut d);
            (p.name.to_owned(), d)
        })
        .collect()
}

fn order(passes: Vec<Decl>) -> Result<Vec<String>, GraphError> {
    let compiled = CompiledGraph::compile(&decls(passes), &["output".to_owned()])?;
    Ok(compiled.order_names().into_iter().map(String::from).collect())
}

#[test]
fn passes_run_after_what_they_read_whatever_the_registration_order() {
    let got = order(vec![
        pass("present").reads("hdr").writes("output"),
        pass("composite").reads("direct").creates("hdr"),
        pass("direct").reads("gbuffer").creates("direct"),
        pass("gbuffer").creates("gbuffer"),
    ])
    .unwrap();
    assert_eq!(got, ["gbuffer", "direct", "composite", "present"]);
}

#[test]
fn writers_keep_registration_order_and_readers_see_the_last_write() {
    let got = order(vec![
        pass("gbuffer").creates("gbuffer"),
        pass("composite").reads("gbuffer").creates("hdr"),
        pass("present").reads("hdr").writes("output"),
        pass("gi_shade").reads("gbuffer").writes("hdr"),
        pass("fog").writes("hdr"),
    ])
    .unwrap();
    assert_eq!(got, ["gbuffer", "composite", "gi_shade", "fog", "present"]);
}

#[test]
fn passes_nothing_depends_on_are_culled() {
    let got = order(vec![
        pass("gbuffer").creates("gbuffer"),
        pass("debug_unused").reads("gbuffer").creates("debug"),
        pass("present").reads("gbuffer").writes("output"),
    ])
    .unwrap();
    assert_eq!(got, ["gbuffer", "present"]);
}

#[test]
fn independent_passes_keep_registration_order() {
    let got = order(vec![
        pass("b").creates("b"),
        pass("a").creates("a"),
        pass("present").reads("a").reads("b").writes("output"),
    ])
    .unwrap();
    assert_eq!(got, ["b", "a", "present"]);
}

#[test]
fn reading_what_nobody_writes_is_an_error_naming_pass_and_resource() {
    let err = order(vec![pass("present").reads("shadow_map").writes("output")]).unwrap_err();
    assert_eq!(err, GraphError::MissingInput { pass: "present".into(), resource: "shadow_map".into() });
    assert!(err.to_string().contains("'present'") && err.to_string().contains("'shadow_map'"));
}

#[test]
fn writing_an_unknown_resource_is_an_error() {
    let err = order(vec![pass("x").writes("nowhere")]).unwrap_err();
    assert!(matches!(err, GraphError::MissingInput { .. }));
}

#[test]
fn a_cycle_is_an_error_naming_the_passes() {
    let err = order(vec![
        pass("a").reads("y").creates("x"),
        pass("b").reads("x").creates("y"),
        pass("present").reads("x").writes("output"),
    ])
    .unwrap_err();
    match &err {
        GraphError::Cycle { passes } => {
            assert!(passes.contains(&"a".to_owned()) && passes.contains(&"b".to_owned()), "{passes:?}");
        }
        other => panic!("expected a cycle, got {other:?}"),
    }
    assert!(err.to_string().contains("cycle"));
}

#[test]
fn creating_twice_and_duplicate_names_are_errors() {
    let err =
        order(vec![pass("a").creates("x"), pass("b").creates("x"), pass("p").reads("x").writes("output")]).unwrap_err();
    assert!(matches!(err, GraphError::CreatedTwice { .. }), "{err:?}");
    let err = order(vec![pass("a").creates("x"), pass("a").creates("y")]).unwrap_err();
    assert_eq!(err, GraphError::DuplicatePass("a".into()));
}

fn gpu() -> Gpu {
    Gpu::headless().unwrap_or_else(|e| panic!("{e}"))
}

/// gbuffer → a → b → c → present where `a_tmp` dies before `c_tmp` is born: same descriptor,
/// so they share one physical texture; `b_tmp` (different format) does not.
fn pooled_graph() -> RenderGraph {
    let mut g = RenderGraph::new();
    g.import("output");
    let rgba = TextureDesc::target(TextureFormat::Rgba16Float);
    g.add_pass(Box::new(pass("a").creates_desc("a_tmp", rgba)));
    g.add_pass(Box::new(pass("b").reads("a_tmp").creates_desc("b_tmp", TextureDesc::target(TextureFormat::R32Float))));
    g.add_pass(Box::new(pass("c").reads("b_tmp").creates_desc("c_tmp", rgba)));
    g.add_pass(Box::new(pass("half").reads("c_tmp").creates_desc("half_tmp", rgba.scaled(0.5))));
    g.add_pass(Box::new(pass("present").reads("half_tmp").writes("output")));
    g
}

#[test]
fn pool_aliases_disjoint_lifetimes_and_reuses_across_frames() {
    let gpu = gpu();
    let mut g = pooled_graph();
    g.allocate(&gpu, (64, 32)).unwrap();
    let (a, b, c) =
        (g.physical_slot("a_tmp").unwrap(), g.physical_slot("b_tmp").unwrap(), g.physical_slot("c_tmp").unwrap());
    assert_eq!(a, c, "a_tmp and c_tmp have equal descriptors and disjoint lifetimes");
    assert_ne!(a, b);
    assert_eq!(g.pool_stats().live, 3);
    assert_eq!(g.physical_texture("half_tmp").unwrap().width(), 32);
    let allocations = g.pool_stats().allocations;
    // Same size again (a new frame, or a re-compile): nothing is allocated.
    g.invalidate();
    g.allocate(&gpu, (64, 32)).unwrap();
    assert_eq!(g.pool_stats().allocations, allocations);
}

#[test]
fn pool_recreates_targets_on_resize_and_frees_the_old_size() {
    let gpu = gpu();
    let mut g = pooled_graph();
    g.allocate(&gpu, (64, 32)).unwrap();
    g.allocate(&gpu, (200, 100)).unwrap();
    let t = g.physical_texture("a_tmp").unwrap();
    assert_eq!((t.width(), t.height()), (200, 100));
    let h = g.physical_texture("half_tmp").unwrap();
    assert_eq!((h.width(), h.height()), (100, 50));
    assert_eq!(g.pool_stats().live, 3, "old-size textures are released");
}
