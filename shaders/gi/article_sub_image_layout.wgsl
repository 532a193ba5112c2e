// Where the article method's receivers lie in its N×N sub-images (included by article_sub_images.wgsl
// and article_volumes.wgsl, which declare `params`). Receiver q belongs to sub-image
// (q + shift) mod N at (q + shift) / N, `shift` following the whole cells the receivers' grid
// has stepped back as the camera turned (GiParams.receiver_steps): so a point of the world
// keeps its sub-image, and the subset of lights that shades it, as the grid steps (see
// plugin_gi/src/grids.rs). Each sub-image has a row and a column more than ⌈size / N⌉, room for
// the shift.

fn sub_side() -> u32 {
    return max(params.article_interleave, 1u);
}

// A step back of the grid moves a world point to the next receiver, q + 1: the shift is the
// steps taken away (RECEIVER_PERIOD − steps, mod the period as they are, then mod N).
fn sub_shift() -> vec2u {
    return (RECEIVER_PERIOD - receiver_steps(params)) % RECEIVER_PERIOD % sub_side();
}

// A sub-image's size in receivers.
fn sub_size() -> vec2u {
    return (params.indirect_size + sub_side() - 1u) / sub_side() + 1u;
}

// Where receiver q lies in the target of sub-images.
fn sub_place(q: vec2u) -> vec2i {
    let n = sub_side();
    let shifted = q + sub_shift();
    return vec2i((shifted % n) * sub_size() + shifted / n);
}

// The sub-image (x + N·y) at pixel p of the target, and the receiver there (x < 0 where none).
struct SubPixel {
    subset: u32,
    q: vec2i,
};

fn sub_pixel(p: vec2u) -> SubPixel {
    let n = sub_side();
    let tile = p / sub_size();
    let q = vec2i((p % sub_size()) * n + tile) - vec2i(sub_shift());
    let valid = all(tile < vec2u(n)) && all(q >= vec2i(0)) && all(q < vec2i(params.indirect_size));
    return SubPixel(tile.y * n + tile.x, select(vec2i(-1), q, valid));
}
