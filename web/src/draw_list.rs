//! What a frame draws, as one flat `f32` array the page reads straight from the module's
//! memory: records of `[style, len, len numbers...]`, in canvas pixels (y down), drawn in
//! order by `web/main.js`.

/// What a record is, and so how `main.js` draws its numbers. The values are the page's too.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Style {
    /// `[x0, y, x1, y]`: the snow's edge, filled below.
    Snow = 0,
    /// A polyline `[x, y, ...]`: one piece of the rope as drawn (the smooth curve).
    Rope = 1,
    /// A polyline `[x, y, ...]`: the rope's particles, raw (straight between them).
    Particles = 2,
    /// `[x, y, r, pivot x, pivot y]`: the hand, on the arm that whirls it round the pivot.
    Hand = 3,
    /// `[x, y, r]`: the penguin.
    Penguin = 4,
    /// Points `[x, y, ...]`: the penguin's trail.
    Trail = 5,
    /// `[x, y]`: where the closed-form arc meets the snow.
    Target = 6,
    /// `[horizon y, time s]`: the sky and the sea.
    Sea = 7,
    /// `[x0, y0, x1, y1, x2, y2, r, g, b]`: a flat triangle, colour 0..255.
    Triangle = 8,
    /// `[x0, y0, x1, y1, width]`: a mast, a boom or a gaff.
    Spar = 9,
    /// `[x, y, r, reach]`: a hook in the roof; `reach` 1 when a throw would catch it now.
    Hook = 10,
    /// A polyline `[x, y, ...]`: the cave's roof, filled above.
    Roof = 11,
}

/// A frame's records; kept between frames so that drawing allocates nothing once warm.
#[derive(Default)]
pub struct DrawList {
    numbers: Vec<f32>,
}

impl DrawList {
    /// Forgets the last frame.
    pub fn clear(&mut self) {
        self.numbers.clear();
    }

    /// Appends a record.
    pub fn push(&mut self, style: Style, numbers: &[f32]) {
        self.numbers.push(f32::from(style as u8));
        self.numbers.push(numbers.len() as f32);
        self.numbers.extend_from_slice(numbers);
    }

    /// Appends a record of points.
    pub fn points(&mut self, style: Style, points: impl IntoIterator<Item = [f32; 2]>) {
        self.numbers.push(f32::from(style as u8));
        let len_at = self.numbers.len();
        self.numbers.push(0.0);
        self.numbers.extend(points.into_iter().flatten());
        self.numbers[len_at] = (self.numbers.len() - len_at - 1) as f32;
    }

    /// The records, as the page reads them.
    pub fn numbers(&self) -> &[f32] {
        &self.numbers
    }

    /// The records in order, as `(style, numbers)`.
    pub fn records(&self) -> impl Iterator<Item = (u8, &[f32])> {
        let mut rest = &self.numbers[..];
        core::iter::from_fn(move || {
            let (&[style, len], tail) = rest.split_first_chunk::<2>()?;
            let (numbers, tail) = tail.split_at_checked(len as usize)?;
            rest = tail;
            Some((style as u8, numbers))
        })
    }
}
