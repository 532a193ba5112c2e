//! The pistol in the player's hand, drawn flat over the frame like Doom's weapon sprites: seen
//! from behind, sights on the crosshair's line, kicking up when it fires, a flash at the muzzle,
//! lowered while reloading. It is not a mesh in the world on purpose: a gun 0.4 m from the eye
//! would be the brightest thing in the attached headlamp's reflective shadow map and flood the
//! indirect light.

use engine::egui::{pos2, vec2, Color32, Pos2, Rect, Shape, Stroke};

/// How the gun is held this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GunPose {
    /// 1 as a shot leaves, falling to 0 before the next.
    pub recoil: f32,
    /// 1 at the brightest of the muzzle flash, 0 without one.
    pub flash: f32,
    /// 0 held up, 1 fully lowered (mid-reload).
    pub lowered: f32,
}

const METAL: Color32 = Color32::from_rgb(38, 39, 44);
const EDGE: Color32 = Color32::from_rgb(92, 94, 102);
const GRIP: Color32 = Color32::from_rgb(30, 26, 24);

/// The gun's shapes for a screen `screen`, its pose `pose`.
pub fn shapes(screen: Rect, pose: GunPose) -> Vec<Shape> {
    let h = screen.height();
    let kick = pose.recoil.clamp(0.0, 1.0) * 0.05 * h;
    let drop = pose.lowered.clamp(0.0, 1.0) * 0.3 * h;
    // The slide's top centre: below the crosshair, right of centre, as a right hand holds it.
    // Right of the HUD's centred hint line, clear of the ammo counter.
    let top = pos2(screen.center().x + 0.42 * h, screen.bottom() - 0.3 * h - kick + drop);
    let (w, slide_h) = (0.15 * h, 0.1 * h);
    let slide = Rect::from_min_size(pos2(top.x - w / 2.0, top.y), vec2(w, slide_h));
    let mut out = Vec::new();
    // The grip, from under the slide to below the screen's edge, a little canted.
    let grip = vec![
        pos2(slide.left() + 0.1 * w, slide.bottom()),
        pos2(slide.right() - 0.05 * w, slide.bottom()),
        pos2(slide.right() + 0.25 * w, screen.bottom() + 0.05 * h),
        pos2(slide.left() + 0.2 * w, screen.bottom() + 0.05 * h),
    ];
    out.push(Shape::convex_polygon(grip, GRIP, Stroke::new(1.0, Color32::BLACK)));
    out.push(Shape::rect_filled(slide, 0.12 * w, METAL));
    out.push(Shape::line_segment(
        [slide.left_top() + vec2(0.1 * w, 1.0), slide.right_top() + vec2(-0.1 * w, 1.0)],
        Stroke::new(2.0, EDGE),
    ));
    // The rear sight's two posts and the front sight between them.
    let post = vec2(0.2 * w, 0.09 * h * 0.25);
    for x in [slide.left() + 0.08 * w, slide.right() - 0.08 * w - post.x] {
        out.push(Shape::rect_filled(Rect::from_min_size(pos2(x, slide.top() - post.y), post), 1.0, METAL));
    }
    let front = Rect::from_center_size(pos2(top.x, slide.top() - 0.6 * post.y), vec2(0.07 * w, 1.2 * post.y));
    out.push(Shape::rect_filled(front, 1.0, EDGE));
    if pose.flash > 0.0 {
        out.extend(muzzle_flash(pos2(top.x, slide.top() - 1.6 * post.y), 0.07 * h, pose.flash));
    }
    out
}

/// A star of light at the muzzle, fading with `strength`.
fn muzzle_flash(at: Pos2, size: f32, strength: f32) -> Vec<Shape> {
    let s = strength.clamp(0.0, 1.0);
    // Eight spikes, each a convex kite from the centre (egui fills convex shapes only).
    let star = |radius: f32, color: Color32, out: &mut Vec<Shape>| {
        let point = |i: i32, r: f32| {
            let angle = i as f32 / 16.0 * std::f32::consts::TAU;
            at + vec2(angle.cos(), angle.sin() * 0.7) * r
        };
        for spike in 0..8 {
            let i = spike * 2;
            let kite = vec![at, point(i - 1, 0.45 * radius), point(i, radius), point(i + 1, 0.45 * radius)];
            out.push(Shape::convex_polygon(kite, color, Stroke::NONE));
        }
    };
    let alpha = |a: f32| (a * s * 255.0) as u8;
    let mut out = Vec::new();
    star(size * (0.8 + 0.4 * s), Color32::from_rgba_unmultiplied(255, 170, 60, alpha(0.8)), &mut out);
    out.push(Shape::circle_filled(at, size * 0.3, Color32::from_rgba_unmultiplied(255, 240, 200, alpha(1.0))));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn screen() -> Rect {
        Rect::from_min_size(Pos2::ZERO, vec2(1280.0, 720.0))
    }

    fn top(shapes: &[Shape]) -> f32 {
        shapes.iter().map(|s| s.visual_bounding_rect().top()).fold(f32::MAX, f32::min)
    }

    #[test]
    fn the_gun_kicks_flashes_and_lowers() {
        let rest = shapes(screen(), GunPose::default());
        assert!(rest.iter().all(|s| screen().expand(100.0).contains_rect(s.visual_bounding_rect())));
        assert!(top(&rest) > screen().center().y, "below the crosshair");
        let fired = shapes(screen(), GunPose { recoil: 1.0, flash: 1.0, lowered: 0.0 });
        assert!(fired.len() > rest.len(), "the flash adds its light");
        assert!(top(&fired) < top(&rest), "the shot kicks it up");
        let reloading = shapes(screen(), GunPose { lowered: 1.0, ..Default::default() });
        assert!(top(&reloading) > top(&rest) + 100.0, "reloading lowers it");
    }
}
