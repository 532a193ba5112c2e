//! Render graph: ordering from stages, declarations and explicit orders; culling; the errors
//! an unclear graph is refused with; and the descriptor-keyed pool (reuse across frames,
//! aliasing of disjoint lifetimes, re-creation on resize).

use engine::gpu::Gpu;
use engine::graph::{
    BufferDesc, GraphError, Handle, Image, PassContext, PassDecl, RenderGraph, RenderPass, Stage, TextureDesc,
};
use engine::view_state::ViewState;
use engine::wgpu::{BufferUsages, TextureFormat};

/// A pass that only declares; `run` records nothing.
#[derive(Default)]
struct Fake {
    name: &'static str,
    reads: Vec<Handle<Image>>,
    creates: Vec<(Handle<Image>, TextureDesc)>,
    writes: Vec<Handle<Image>>,
}

fn pass(name: &'static str) -> Fake {
    Fake { name, ..Fake::default() }
}

fn rgba() -> TextureDesc {
    TextureDesc::target(TextureFormat::Rgba16Float)
}

impl Fake {
    fn reads(mut self, r: Handle<Image>) -> Self {
        self.reads.push(r);
        self
    }
    fn creates(self, r: Handle<Image>) -> Self {
        self.creates_desc(r, rgba())
    }
    fn creates_desc(mut self, r: Handle<Image>, d: TextureDesc) -> Self {
        self.creates.push((r, d));
        self
    }
    fn writes(mut self, r: Handle<Image>) -> Self {
        self.writes.push(r);
        self
    }
}

impl RenderPass for Fake {
    type Io = ();
    fn name(&self) -> &str {
        self.name
    }
    fn declare(&self, d: &mut PassDecl<'_>) {
        for r in &self.reads {
            d.read(*r);
        }
        for (r, desc) in &self.creates {
            d.create(*r, *desc);
        }
        for w in &self.writes {
            d.write(*w);
        }
    }
    fn run(&mut self, _io: &(), _ctx: &mut PassContext<'_>) {}
}

/// The order the graph runs its passes in, or its error.
fn order(g: &mut RenderGraph) -> Result<Vec<String>, GraphError> {
    let compiled = g.compile((64, 32), &ViewState::default())?;
    Ok(compiled.order_names().into_iter().map(String::from).collect())
}

#[test]
fn passes_run_after_what_they_read_whatever_the_registration_order() {
    let mut g = RenderGraph::new();
    let (output, hdr, direct, gbuffer) = (g.import_image("output"), g.image("hdr"), g.image("direct"), g.image("gb"));
    g.add_pass(Stage::Lighting, pass("present").reads(hdr).writes(output));
    g.add_pass(Stage::Lighting, pass("composite").reads(direct).creates(hdr));
    g.add_pass(Stage::Lighting, pass("direct").reads(gbuffer).creates(direct));
    g.add_pass(Stage::Lighting, pass("gbuffer").creates(gbuffer));
    assert_eq!(order(&mut g).unwrap(), ["gbuffer", "direct", "composite", "present"]);
}

#[test]
fn stages_order_writers_and_readers_see_the_last_write() {
    let mut g = RenderGraph::new();
    let (output, hdr, gbuffer) = (g.import_image("output"), g.image("hdr"), g.image("gbuffer"));
    // Registered out of order: the stages put them right.
    g.add_pass(Stage::ViewModels, pass("weapon").writes(hdr));
    g.add_pass(Stage::Present, pass("present").reads(hdr).writes(output));
    g.add_pass(Stage::Composite, pass("gi_shade").reads(gbuffer).writes(hdr));
    g.add_pass(Stage::GBuffer, pass("gbuffer").creates(gbuffer));
    g.add_pass(Stage::Composite, pass("composite").reads(gbuffer).creates(hdr));
    assert_eq!(order(&mut g).unwrap(), ["gbuffer", "composite", "gi_shade", "weapon", "present"]);
}

#[test]
fn two_writers_nothing_orders_are_an_error_naming_both_until_one_is_declared_after() {
    let build = |explicit: bool| {
        let mut g = RenderGraph::new();
        let (output, hdr) = (g.import_image("output"), g.image("hdr"));
        g.add_pass(Stage::Composite, pass("composite").creates(hdr));
        g.add_pass(Stage::Composite, pass("fog").writes(hdr));
        let glow = g.add_pass(Stage::Composite, pass("glow").writes(hdr));
        if explicit {
            glow.before("fog");
        }
        g.add_pass(Stage::Present, pass("present").reads(hdr).writes(output));
        g
    };
    let err = order(&mut build(false)).unwrap_err();
    assert_eq!(err, GraphError::AmbiguousOrder { resource: "hdr".into(), first: "fog".into(), second: "glow".into() });
    assert!(err.to_string().contains("'fog'") && err.to_string().contains("'glow'"), "{err}");
    // Declared: glow before fog, though registered after it.
    assert_eq!(order(&mut build(true)).unwrap(), ["composite", "glow", "fog", "present"]);
}

#[test]
fn a_replaced_pass_is_gone_and_its_replacement_takes_its_stage_and_orders() {
    let mut g = RenderGraph::new();
    let (output, hdr, gbuffer, gi) = (g.import_image("output"), g.image("hdr"), g.image("gbuffer"), g.image("gi"));
    g.add_pass(Stage::GBuffer, pass("gbuffer").creates(gbuffer));
    g.add_pass(Stage::Composite, pass("composite").reads(gbuffer).creates(hdr));
    g.add_pass(Stage::Composite, pass("fog").writes(hdr)).after("composite");
    g.add_pass(Stage::Present, pass("present").reads(hdr).writes(output));
    // Registered before its input's maker, in an earlier stage than the pass it replaces: it
    // runs where `composite` did, after what it reads, before `fog`, which named `composite`.
    g.add_pass(Stage::Indirect, pass("gi").reads(gbuffer).creates(gi));
    g.replace_pass("composite", pass("gi_composite").reads(gi).reads(gbuffer).creates(hdr));
    assert_eq!(order(&mut g).unwrap(), ["gbuffer", "gi", "gi_composite", "fog", "present"]);
    assert!(!g.pass_names().contains(&"composite".to_string()));
}

#[test]
fn replacing_a_pass_the_graph_does_not_have_is_an_error() {
    let mut g = RenderGraph::new();
    let (output, hdr) = (g.import_image("output"), g.image("hdr"));
    g.add_pass(Stage::Composite, pass("composite").creates(hdr));
    g.add_pass(Stage::Present, pass("present").reads(hdr).writes(output));
    g.replace_pass("compositor", pass("gi_composite").creates(hdr));
    let err = order(&mut g).unwrap_err();
    assert_eq!(err, GraphError::UnknownPass("compositor".into()));
    assert!(err.to_string().contains("'compositor'"), "{err}");
}

#[test]
fn an_explicit_order_naming_no_pass_is_an_error() {
    let mut g = RenderGraph::new();
    let output = g.import_image("output");
    g.add_pass(Stage::Present, pass("present").writes(output)).after("tonemap");
    assert_eq!(order(&mut g).unwrap_err(), GraphError::UnknownPass("tonemap".into()));
}

#[test]
fn reading_what_a_later_stage_makes_is_a_cycle() {
    let mut g = RenderGraph::new();
    let (output, hdr, gbuffer) = (g.import_image("output"), g.image("hdr"), g.image("gbuffer"));
    g.add_pass(Stage::GBuffer, pass("gbuffer").reads(hdr).creates(gbuffer));
    g.add_pass(Stage::Composite, pass("composite").creates(hdr));
    g.add_pass(Stage::Present, pass("present").reads(gbuffer).writes(output));
    match order(&mut g).unwrap_err() {
        GraphError::Cycle { passes } => assert!(passes.contains(&"gbuffer".to_owned()), "{passes:?}"),
        other => panic!("expected a cycle, got {other:?}"),
    }
}

#[test]
fn passes_nothing_depends_on_are_culled() {
    let mut g = RenderGraph::new();
    let (output, gbuffer, debug) = (g.import_image("output"), g.image("gbuffer"), g.image("debug"));
    g.add_pass(Stage::GBuffer, pass("gbuffer").creates(gbuffer));
    g.add_pass(Stage::Composite, pass("debug_unused").reads(gbuffer).creates(debug));
    g.add_pass(Stage::Present, pass("present").reads(gbuffer).writes(output));
    assert_eq!(order(&mut g).unwrap(), ["gbuffer", "present"]);
}

#[test]
fn independent_passes_keep_registration_order() {
    let mut g = RenderGraph::new();
    let (output, a, b) = (g.import_image("output"), g.image("a"), g.image("b"));
    g.add_pass(Stage::Lighting, pass("b").creates(b));
    g.add_pass(Stage::Lighting, pass("a").creates(a));
    g.add_pass(Stage::Present, pass("present").reads(a).reads(b).writes(output));
    assert_eq!(order(&mut g).unwrap(), ["b", "a", "present"]);
}

#[test]
fn reading_what_nobody_creates_is_an_error_naming_pass_and_resource() {
    let mut g = RenderGraph::new();
    let (output, shadow) = (g.import_image("output"), g.image("shadow_map"));
    g.add_pass(Stage::Present, pass("present").reads(shadow).writes(output));
    let err = order(&mut g).unwrap_err();
    assert_eq!(err, GraphError::MissingInput { pass: "present".into(), resource: "shadow_map".into() });
    assert!(err.to_string().contains("'present'") && err.to_string().contains("'shadow_map'"));
}

#[test]
fn creating_an_import_or_twice_duplicate_names_and_labels_are_errors() {
    let mut g = RenderGraph::new();
    let output = g.import_image("output");
    g.add_pass(Stage::Present, pass("present").creates(output));
    assert!(matches!(order(&mut g).unwrap_err(), GraphError::CreatesSupplied { .. }));

    let mut g = RenderGraph::new();
    let (output, x) = (g.import_image("output"), g.image("x"));
    g.add_pass(Stage::Lighting, pass("a").creates(x));
    g.add_pass(Stage::Lighting, pass("b").creates(x));
    g.add_pass(Stage::Present, pass("p").reads(x).writes(output));
    assert!(matches!(order(&mut g).unwrap_err(), GraphError::CreatedTwice { .. }));

    let mut g = RenderGraph::new();
    let (x, y) = (g.image("x"), g.image("y"));
    g.add_pass(Stage::Lighting, pass("a").creates(x));
    g.add_pass(Stage::Lighting, pass("a").creates(y));
    assert_eq!(order(&mut g).unwrap_err(), GraphError::DuplicatePass("a".into()));

    let mut g = RenderGraph::new();
    g.image("hdr");
    g.image("hdr");
    assert_eq!(order(&mut g).unwrap_err(), GraphError::DuplicateLabel("hdr".into()));
}

/// Creates a uniform and writes it; `second` also writes it when set.
struct Uniform {
    name: &'static str,
    buffer: engine::graph::Handle<engine::graph::Buffer>,
    creates: bool,
    output: Handle<Image>,
}

impl RenderPass for Uniform {
    type Io = ();
    fn name(&self) -> &str {
        self.name
    }
    fn declare(&self, d: &mut PassDecl<'_>) {
        let usage = BufferUsages::UNIFORM | BufferUsages::COPY_DST;
        if self.creates {
            d.create(self.buffer, BufferDesc { size: 16, usage });
        } else {
            d.write(self.buffer);
        }
        d.write(self.output);
    }
    fn run(&mut self, _io: &(), _ctx: &mut PassContext<'_>) {}
}

#[test]
fn a_uniform_has_one_writer_a_frame() {
    let mut g = RenderGraph::new();
    let (output, params) = (g.import_image("output"), g.persistent_buffer("params"));
    g.add_pass(Stage::Lighting, Uniform { name: "flux", buffer: params, creates: true, output });
    g.add_pass(Stage::Indirect, Uniform { name: "reference", buffer: params, creates: false, output });
    let err = order(&mut g).unwrap_err();
    let expected = GraphError::UniformWrittenTwice {
        resource: "params".into(),
        creator: "flux".into(),
        writer: "reference".into(),
    };
    assert_eq!(err, expected);
}

fn gpu() -> Gpu {
    Gpu::headless().unwrap_or_else(|e| panic!("{e}"))
}

/// a → b → c → present where `a_tmp` dies before `c_tmp` is born: same descriptor, so they
/// share one physical texture; `b_tmp` (different format) does not.
fn pooled_graph() -> (RenderGraph, [Handle<Image>; 4]) {
    let mut g = RenderGraph::new();
    let output = g.import_image("output");
    let tmp = [g.image("a_tmp"), g.image("b_tmp"), g.image("c_tmp"), g.image("half_tmp")];
    let [a, b, c, half] = tmp;
    g.add_pass(Stage::Lighting, pass("a").creates(a));
    g.add_pass(Stage::Lighting, pass("b").reads(a).creates_desc(b, TextureDesc::target(TextureFormat::R32Float)));
    g.add_pass(Stage::Lighting, pass("c").reads(b).creates(c));
    g.add_pass(Stage::Lighting, pass("half").reads(c).creates_desc(half, rgba().scaled(0.5)));
    g.add_pass(Stage::Present, pass("present").reads(half).writes(output));
    (g, tmp)
}

#[test]
fn pool_aliases_disjoint_lifetimes_and_reuses_across_frames() {
    let (gpu, view) = (gpu(), ViewState::default());
    let (mut g, [a, b, c, half]) = pooled_graph();
    g.allocate(&gpu, (64, 32), &view).unwrap();
    let slot = |h| g.physical_slot(h).unwrap();
    assert_eq!(slot(a), slot(c), "a_tmp and c_tmp have equal descriptors and disjoint lifetimes");
    assert_ne!(slot(a), slot(b));
    assert_eq!(g.pool_stats().live, 3);
    assert_eq!(g.physical_texture(half).unwrap().width(), 32);
    let allocations = g.pool_stats().allocations;
    // Same size again (a new frame): nothing is allocated.
    g.allocate(&gpu, (64, 32), &view).unwrap();
    assert_eq!(g.pool_stats().allocations, allocations);
}

#[test]
fn pool_recreates_targets_on_resize_and_frees_the_old_size() {
    let (gpu, view) = (gpu(), ViewState::default());
    let (mut g, [a, _, _, half]) = pooled_graph();
    g.allocate(&gpu, (64, 32), &view).unwrap();
    g.allocate(&gpu, (200, 100), &view).unwrap();
    let t = g.physical_texture(a).unwrap();
    assert_eq!((t.width(), t.height()), (200, 100));
    let h = g.physical_texture(half).unwrap();
    assert_eq!((h.width(), h.height()), (100, 50));
    assert_eq!(g.pool_stats().live, 3, "old-size textures are released");
}
