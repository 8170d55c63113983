//! Planar kinematics of a body's reference point: A(θ) s and its derivatives (docs/physics.md §1).

/// A plain 2-vector (Copy, no allocation). nalgebra's `Vector2` is used where its algebra helps;
/// the hot path works on this to keep the arithmetic explicit.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct V2 {
    pub x: f64,
    pub y: f64,
}

impl V2 {
    #[inline]
    pub const fn new(x: f64, y: f64) -> Self {
        V2 { x, y }
    }
    #[inline]
    pub fn add(self, o: V2) -> V2 {
        V2::new(self.x + o.x, self.y + o.y)
    }
    #[inline]
    pub fn sub(self, o: V2) -> V2 {
        V2::new(self.x - o.x, self.y - o.y)
    }
    #[inline]
    pub fn scale(self, k: f64) -> V2 {
        V2::new(self.x * k, self.y * k)
    }
    #[inline]
    pub fn dot(self, o: V2) -> f64 {
        self.x * o.x + self.y * o.y
    }
    /// z-component of the cross product self × o.
    #[inline]
    pub fn cross(self, o: V2) -> f64 {
        self.x * o.y - self.y * o.x
    }
    /// The vector turned +90°.
    #[inline]
    pub fn perp(self) -> V2 {
        V2::new(-self.y, self.x)
    }
    /// Length, as `√(x² + y²)` (lengths in a mechanism are far from overflow; `hypot`'s
    /// rescaling cost 3 % of a dry cycle), falling back to `hypot` where `x² + y²` is subnormal
    /// (an eccentricity within 1e-154 m of the centre), so that `v / |v|` stays a unit vector.
    #[inline]
    pub fn norm(self) -> f64 {
        let s = self.x * self.x + self.y * self.y;
        if s >= f64::MIN_POSITIVE {
            s.sqrt()
        } else {
            self.x.hypot(self.y)
        }
    }
}

impl From<[f64; 2]> for V2 {
    fn from(a: [f64; 2]) -> V2 {
        V2::new(a[0], a[1])
    }
}

impl From<nalgebra::Vector2<f64>> for V2 {
    fn from(v: nalgebra::Vector2<f64>) -> V2 {
        V2::new(v.x, v.y)
    }
}

/// Position and velocity of one body with cos θ, sin θ precomputed once per right-hand side.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BodyKin {
    pub x: f64,
    pub y: f64,
    pub th: f64,
    pub vx: f64,
    pub vy: f64,
    /// Angular speed θ̇ [rad/s].
    pub w: f64,
    pub c: f64,
    pub s: f64,
}

impl BodyKin {
    /// The ground: at rest, at the origin, not rotated.
    pub const GROUND: BodyKin = BodyKin { x: 0.0, y: 0.0, th: 0.0, vx: 0.0, vy: 0.0, w: 0.0, c: 1.0, s: 0.0 };

    #[inline]
    pub fn new(q: &[f64], qd: &[f64]) -> Self {
        let (s, c) = q[2].sin_cos();
        BodyKin { x: q[0], y: q[1], th: q[2], vx: qd[0], vy: qd[1], w: qd[2], c, s }
    }
    #[inline]
    pub fn r(&self) -> V2 {
        V2::new(self.x, self.y)
    }
    #[inline]
    pub fn v(&self) -> V2 {
        V2::new(self.vx, self.vy)
    }
    /// A(θ) s: a body-fixed vector in the global frame.
    #[inline]
    pub fn rot(&self, s: V2) -> V2 {
        V2::new(self.c * s.x - self.s * s.y, self.s * s.x + self.c * s.y)
    }
    /// Global position of the body-fixed point s'.
    #[inline]
    pub fn point(&self, s: V2) -> V2 {
        self.r().add(self.rot(s))
    }
    /// Global velocity of the body-fixed point s': ṙ + θ̇ (A s)⊥.
    #[inline]
    pub fn point_velocity(&self, s: V2) -> V2 {
        self.v().add(self.rot(s).perp().scale(self.w))
    }
}
