//! When each GI pass runs. The plugin adds every pass with the condition on the frame's
//! description ([`GiFrame`]) under which it runs ([`When`]); a pass never decides that
//! itself. On a frame the condition does not hold the pass declares nothing, and the render
//! graph leaves it out. The GI switched off needs no condition: the composite then reads
//! nothing of the GI, and the graph culls every pass whose result nothing reads (a debug view
//! shown with the GI off still gets the passes it needs).

use engine::graph::{PassContext, PassDecl, RenderPass};

use crate::frame::GiFrame;
use crate::settings::Method;
use crate::shared::GiHandle;

/// What a frame must be for a pass to run: each of these that is set.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct When {
    /// `gi.enabled`: for a pass whose result the engine reads whatever the GI does (the view
    /// models' irradiance).
    enabled: bool,
    /// The first bounce's method.
    method: Option<Method>,
    /// `gi.visibility` on.
    visibility: bool,
    /// At least this many bounces computed (beyond 1: the cuts' method with the lamp on the
    /// head; the article's method is its one bounce, see docs/gi.md).
    bounce: u32,
}

impl When {
    /// Every frame: whether it runs is what reads it.
    pub const ALWAYS: When = When { enabled: false, method: None, visibility: false, bounce: 1 };
    /// Whenever the GI is on.
    pub const ENABLED: When = When { enabled: true, ..When::ALWAYS };

    /// The first bounce is by `method`.
    pub const fn method(method: Method) -> When {
        When { method: Some(method), ..When::ALWAYS }
    }

    /// The `k`th bounce is computed.
    pub const fn bounce(k: u32) -> When {
        When { method: Some(Method::Cuts), bounce: k, ..When::ALWAYS }
    }

    /// … and light is stopped by the surfaces between.
    pub const fn with_visibility(self) -> When {
        When { visibility: true, ..self }
    }

    pub fn holds(&self, frame: &GiFrame) -> bool {
        (frame.enabled() || !self.enabled)
            && self.method.is_none_or(|m| frame.settings.method == m)
            && (!self.visibility || frame.visibility())
            && self.bounce <= frame.bounces()
    }
}

/// A GI pass: as a render-graph pass, given the frame's description to declare and run by.
pub(crate) trait GiPass: 'static {
    type Io: 'static;
    fn name(&self) -> &str;
    fn declare(&self, d: &mut PassDecl<'_>, frame: &GiFrame) -> Self::Io;
    fn run(&mut self, io: &Self::Io, frame: &GiFrame, ctx: &mut PassContext<'_>);
}

/// The name of stage `stage`'s pass for bounce `k`: `gi_STAGE` for the first, `gi_bounceK_STAGE`
/// for a further one.
pub(crate) fn bounce_pass_name(stage: &str, k: u32) -> String {
    if k == 1 {
        format!("gi_{stage}")
    } else {
        format!("gi_bounce{k}_{stage}")
    }
}

/// A GI pass with its condition, as the render graph takes it.
pub(crate) struct Scheduled<P> {
    pub pass: P,
    pub when: When,
    pub handle: GiHandle,
}

impl<P: GiPass> RenderPass for Scheduled<P> {
    /// The frame it was declared for, and its tokens; None on frames it does not run.
    type Io = Option<(GiFrame, P::Io)>;

    fn name(&self) -> &str {
        self.pass.name()
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> Self::Io {
        let frame = self.handle.frame(d.size(), d.view().headlamp.attached);
        self.when.holds(&frame).then(|| {
            let io = self.pass.declare(d, &frame);
            (frame, io)
        })
    }

    fn run(&mut self, io: &Self::Io, ctx: &mut PassContext<'_>) {
        if let Some((frame, io)) = io {
            self.pass.run(io, frame, ctx);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::GiSettings;

    #[test]
    fn each_condition_holds_on_the_frames_it_names() {
        let frame = |settings: GiSettings, attached| GiFrame::of(&settings, (640, 360), attached);
        let base = GiSettings::default();
        let cuts = frame(base.clone(), true);
        let article = frame(GiSettings { method: Method::Article, bounces: 3, ..base.clone() }, true);
        let off = frame(GiSettings { enabled: false, ..base.clone() }, true);
        let blind = frame(GiSettings { visibility: 0, ..base.clone() }, true);
        let three = frame(GiSettings { bounces: 3, ..base.clone() }, true);
        let detached = frame(GiSettings { bounces: 3, ..base.clone() }, false);
        assert!(When::ENABLED.holds(&cuts) && When::ENABLED.holds(&article) && !When::ENABLED.holds(&off));
        assert!(When::ALWAYS.holds(&off) && When::method(Method::Cuts).holds(&off), "the graph culls them");
        assert!(When::method(Method::Cuts).holds(&cuts) && !When::method(Method::Cuts).holds(&article));
        assert!(When::method(Method::Article).holds(&article) && !When::method(Method::Article).holds(&cuts));
        let sight = When::method(Method::Cuts).with_visibility();
        assert!(sight.holds(&cuts) && !sight.holds(&blind) && !sight.holds(&article));
        // Further bounces: the cuts' method with the lamp on the head.
        assert!(When::bounce(1).holds(&cuts) && !When::bounce(2).holds(&cuts));
        assert!(When::bounce(3).holds(&three) && !When::bounce(2).holds(&article) && !When::bounce(2).holds(&detached));
        assert!(When::bounce(2).with_visibility().holds(&three));
    }
}
