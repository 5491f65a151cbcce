//! The immovable bodies a ball meets, by kind and id: the table's boundaries, the box's walls
//! and the fixed ball obstacles (how a boundary map's rows and portraits name them).

/// Which immovable body a ball met: a boundary map's row, a portrait.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Body {
    /// A boundary of [`crate::Table::boundaries`], by id.
    Boundary(usize),
    /// A wall of the box: axis, and the upper one (at `L_k`) if `true`.
    BoxWall(usize, bool),
    /// A fixed ball obstacle, by index.
    Obstacle(usize),
}

impl Body {
    /// The CSV's `kind` and `id` (a box wall's id is `2 axis + upper`).
    pub fn kind_id(self) -> (&'static str, usize) {
        match self {
            Body::Boundary(b) => ("boundary", b),
            Body::BoxWall(k, upper) => ("box-wall", 2 * k + usize::from(upper)),
            Body::Obstacle(o) => ("obstacle", o),
        }
    }

    /// A file-name stem: `boundary3`, `box-wall1`, `obstacle0`.
    pub fn stem(self) -> String {
        let (kind, id) = self.kind_id();
        format!("{kind}{id}")
    }
}
