//! The course's Java classes by API (docs/grade.md, "The Tick 1 skeleton's API"): the years
//! group into five skeletons, each adding to or changing the one before. What a submission may
//! call, which constructors the loader calls, and so which skeleton grade compiles it against.

/// A skeleton of the course's classes. A closed set, in time order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Api {
    /// 2016-17's Tick 2, package `gfx.tick2`: colours are `Vector3`s.
    Tick2,
    /// 2017-18's Tick 1: `ColorRGB`, `getPhong_alpha`, `illuminate(..., O)`; materials from the
    /// student's own Sphere and Plane constants.
    T1,
    /// 2018-19: `add(double)`, `power`, `inv` on vectors and colours (the tone map's).
    T2,
    /// 2019-20 to 2022-23: the loader reads materials and calls 7-argument constructors.
    T3,
    /// 2023-24: transmittance (an 8-argument Sphere), `subtract(double)`, `isZero`, `-r WxH`.
    T4,
}

impl Api {
    /// The name docs/grade.md gives it.
    pub fn name(self) -> &'static str {
        match self {
            Api::Tick2 => "Tick 2",
            Api::T1 => "T1",
            Api::T2 => "T2",
            Api::T3 => "T3",
            Api::T4 => "T4",
        }
    }

    /// The Tick 1 skeletons (2017-18 on), in order.
    pub const TICK1: [Api; 4] = [Api::T1, Api::T2, Api::T3, Api::T4];
}

impl std::fmt::Display for Api {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
