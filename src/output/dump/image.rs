//! `dump ID GROUP image N FILE.*.png type type [keywords]`: a PNG picture of the group's
//! particles every N steps, LAMMPS's syntax and defaults (dump_image.cpp) where gendpde
//! draws the same thing: spheres coloured and sized by type, seen from `view` theta phi
//! through a 30-degree perspective camera that fits the box (`zoom`, `center`, `up`),
//! with the box edges and optional axes. Each pixel is a ray traced to the nearest sphere
//! (rank 0 draws, from the positions gathered in ID order).

use crate::base::args::Args;
use crate::output::dump::head::{unknown_key, Dump, Head};
use crate::output::schedule::{Frame, RunOutput, Span};
use gendpde_engine::Vec3;
use gendpde_io::ScriptError;
use std::fs::File;
use std::io::BufWriter;

/// LAMMPS's colours of types 1, 2, ... (cycled).
const TYPE_COLORS: [&str; 6] = ["red", "green", "blue", "yellow", "aqua", "cyan"];

/// The colour names gendpde knows (HTML's values, as LAMMPS's table).
const COLORS: &[(&str, [u8; 3])] = &[
    ("white", [255, 255, 255]),
    ("black", [0, 0, 0]),
    ("red", [255, 0, 0]),
    ("green", [0, 128, 0]),
    ("lime", [0, 255, 0]),
    ("blue", [0, 0, 255]),
    ("yellow", [255, 255, 0]),
    ("aqua", [0, 255, 255]),
    ("cyan", [0, 255, 255]),
    ("magenta", [255, 0, 255]),
    ("orange", [255, 165, 0]),
    ("purple", [128, 0, 128]),
    ("pink", [255, 192, 203]),
    ("brown", [165, 42, 42]),
    ("gray", [128, 128, 128]),
    ("grey", [128, 128, 128]),
    ("silver", [192, 192, 192]),
    ("navy", [0, 0, 128]),
    ("teal", [0, 128, 128]),
    ("olive", [128, 128, 0]),
    ("maroon", [128, 0, 0]),
];

/// Atom types: one, or LAMMPS's range (`*`, `n*`, `*n`, `m*n`).
type Types = std::ops::RangeInclusive<u64>;

/// The camera's field of view (LAMMPS's FOV, pi/6).
const FOV: f64 = std::f64::consts::PI / 6.0;

fn color(a: &Args, name: &str) -> Result<[f64; 3], ScriptError> {
    let known = || COLORS.iter().map(|c| c.0).collect::<Vec<_>>().join(" ");
    let c = COLORS.iter().find(|c| c.0 == name).ok_or_else(|| a.err(format!("Invalid color name '{name}'; known: {}", known())))?.1;
    Ok(c.map(|v| f64::from(v) / 255.0))
}

fn rgb(name: &str) -> [f64; 3] {
    COLORS.iter().find(|c| c.0 == name).map_or([1.0; 3], |c| c.1.map(|v| f64::from(v) / 255.0))
}

pub struct ImageDump {
    head: Head,
    width: usize,
    height: usize,
    /// `view` theta phi in degrees.
    view: [f64; 2],
    zoom: f64,
    /// `center s` Cx Cy Cz: the point looked at, as fractions of the box.
    center: Vec3,
    up: Vec3,
    /// `box yes|no diam`: the edges' diameter per the shortest box length.
    box_diam: Option<f64>,
    /// `axes yes|no length diam`: per the longest and shortest box length.
    axes: Option<[f64; 2]>,
    shiny: f64,
    atoms: bool,
    /// Per-type colours and diameters of dump_modify acolor and adiam, the last that
    /// names a type wins; other types have LAMMPS's defaults (the colours cycled,
    /// diameter 1).
    colors: Vec<(Types, [f64; 3])>,
    diameters: Vec<(Types, f64)>,
    /// `adiam D` of the dump command: one diameter for all.
    diameter: Option<f64>,
    background: [f64; 3],
    box_color: [f64; 3],
}

impl ImageDump {
    /// The words after `dump ID GROUP image N FILE`: `color diameter [keyword value ...]`.
    pub fn parse(head: Head, a: &mut Args) -> Result<Self, ScriptError> {
        if !head.file.ends_with(".png") {
            return Err(a.err(format!("dump image file '{}': gendpde writes PNG only (FILE.png; no .jpg or .ppm)", head.file)));
        }
        if !head.once && !head.file.contains('*') {
            return Err(a.err("Dump image requires one snapshot per file (a '*' in the file name)"));
        }
        for what in ["color", "diameter"] {
            match a.word(&format!("the atom attribute of the {what} (type)"))? {
                "type" => {}
                w => return Err(a.err(format!("dump image {what} '{w}': gendpde colours and sizes atoms by type only"))),
            }
        }
        let mut d = Self {
            head,
            width: 512,
            height: 512,
            view: [60.0, 30.0],
            zoom: 1.0,
            center: [0.5; 3],
            up: [0.0, 0.0, 1.0],
            box_diam: Some(0.02),
            axes: None,
            shiny: 1.0,
            atoms: true,
            colors: Vec::new(),
            diameters: Vec::new(),
            diameter: None,
            background: [0.0; 3],
            box_color: rgb("yellow"),
        };
        while !d.head.at_end(a) {
            match a.word("a dump image keyword")? {
                "size" => {
                    let (w, h) = (a.u64("the image width")?, a.u64("the image height")?);
                    if w == 0 || h == 0 || w > 16384 || h > 16384 {
                        return Err(a.err("Illegal dump image command: size must be 1..16384 pixels"));
                    }
                    (d.width, d.height) = (w as usize, h as usize);
                }
                "view" => d.view = [a.f64("theta")?, a.f64("phi")?],
                "zoom" => d.zoom = a.positive("the zoom factor")?,
                "center" => {
                    match a.word("s (static) or d (dynamic)")? {
                        "s" => {}
                        w => return Err(a.err(format!("dump image center {w}: only a static center (s) is supported"))),
                    }
                    d.center = [a.f64("Cx")?, a.f64("Cy")?, a.f64("Cz")?];
                }
                "up" => {
                    d.up = [a.f64("Ux")?, a.f64("Uy")?, a.f64("Uz")?];
                    if norm(d.up) == 0.0 {
                        return Err(a.err("Illegal dump image command: up vector is zero"));
                    }
                }
                "box" => d.box_diam = if a.yes_no("box")? { Some(a.positive("the box line diameter")?) } else { a.f64("the box line diameter").map(|_| None)? },
                "axes" => {
                    let on = a.yes_no("axes")?;
                    let (len, diam) = (a.positive("the axes length")?, a.positive("the axes diameter")?);
                    d.axes = on.then_some([len, diam]);
                }
                "shiny" => d.shiny = a.non_negative("the shininess")?.min(1.0),
                "atom" => d.atoms = a.yes_no("atom")?,
                "adiam" => d.diameter = Some(a.positive("the atom diameter")?),
                "ssao" => {
                    if a.yes_no("ssao")? {
                        return Err(a.err("dump image ssao yes: ambient occlusion is not supported"));
                    }
                }
                w @ ("bond" | "line" | "tri" | "body" | "fix" | "persp" | "subbox" | "grid" | "gridx" | "gridy" | "gridz" | "fsaa") => {
                    return Err(a.err(format!("dump image keyword '{w}' is not supported (gendpde draws atoms, the box and axes)")))
                }
                w => return Err(a.err(format!("unknown dump image keyword '{w}'; known: size view zoom center up box axes shiny atom adiam ssao"))),
            }
        }
        Ok(d)
    }

    fn type_color(&self, t: u64) -> [f64; 3] {
        self.colors.iter().rev().find(|(r, _)| r.contains(&t)).map_or_else(|| rgb(TYPE_COLORS[(t as usize - 1) % TYPE_COLORS.len()]), |c| c.1)
    }

    fn type_diameter(&self, t: u64) -> f64 {
        self.diameter.unwrap_or_else(|| self.diameters.iter().rev().find(|(r, _)| r.contains(&t)).map_or(1.0, |d| d.1))
    }

    /// The picture of `spheres` (centre, diameter, colour) in the box `lo`..`hi`.
    fn render(&self, lo: Vec3, hi: Vec3, spheres: &[(Vec3, f64, [f64; 3])]) -> Vec<u8> {
        let (w, h) = (self.width, self.height);
        let len = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
        let target: Vec3 = std::array::from_fn(|k| lo[k] + self.center[k] * len[k]);
        let (theta, phi) = (self.view[0].to_radians(), self.view[1].to_radians());
        let to_camera = [theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()];
        let mut right = cross(self.up, to_camera);
        if norm(right) < 1e-12 {
            // looking along up: any right angle will do
            right = cross([0.0, 1.0, 0.0], to_camera);
        }
        let right = unit(right);
        let up = unit(cross(to_camera, right));
        let forward = to_camera.map(|c| -c);
        // at zoom 1 the box's bounding sphere fills 5/6 of the view, about LAMMPS's framing
        let radius = 0.5 * norm(len);
        let dist = 1.2 * radius / (FOV / 2.0).sin() / self.zoom;
        let eye: Vec3 = std::array::from_fn(|k| target[k] + dist * to_camera[k]);
        let per_pixel = 2.0 * (FOV / 2.0).tan() / w.min(h) as f64;
        let light = unit(add(add(to_camera, scale(up, 0.6)), scale(right, -0.4)));
        let mut depth = vec![f64::INFINITY; w * h];
        let mut image: Vec<[f64; 3]> = vec![self.background; w * h];
        let mut draw = |c: Vec3, d: f64, col: [f64; 3]| {
            let r = 0.5 * d;
            let rel = sub(c, eye);
            let z = dot(rel, forward);
            if z <= r {
                return;
            }
            let (sx, sy) = (dot(rel, right) / (z * per_pixel), dot(rel, up) / (z * per_pixel));
            let pr = r / ((z * z - r * r).sqrt() * per_pixel) + 1.5;
            let (cx, cy) = (w as f64 / 2.0 + sx, h as f64 / 2.0 - sy);
            let (x0, x1) = (((cx - pr).floor().max(0.0)) as usize, ((cx + pr).ceil().min(w as f64)) as usize);
            let (y0, y1) = (((cy - pr).floor().max(0.0)) as usize, ((cy + pr).ceil().min(h as f64)) as usize);
            for py in y0..y1 {
                for px in x0..x1 {
                    let (u, v) = ((px as f64 + 0.5 - w as f64 / 2.0) * per_pixel, (h as f64 / 2.0 - py as f64 - 0.5) * per_pixel);
                    let ray = unit(add(forward, add(scale(right, u), scale(up, v))));
                    // the nearest hit of eye + t ray on the sphere
                    let b = dot(rel, ray);
                    let disc = b * b - dot(rel, rel) + r * r;
                    if disc < 0.0 {
                        continue;
                    }
                    let t = b - disc.sqrt();
                    let k = py * w + px;
                    if t <= 0.0 || t >= depth[k] {
                        continue;
                    }
                    depth[k] = t;
                    let n = unit(sub(scale(ray, t), rel));
                    let diffuse = dot(n, light).max(0.0);
                    let half = unit(add(light, to_camera));
                    let specular = self.shiny * 0.4 * dot(n, half).max(0.0).powi(40);
                    image[k] = col.map(|c| (c * (0.25 + 0.75 * diffuse) + specular).min(1.0));
                }
            }
        };
        if self.atoms {
            for &(c, d, col) in spheres {
                draw(c, d, col);
            }
        }
        // lines as chains of spheres a tenth of their diameter apart
        let mut line = |from: Vec3, to: Vec3, d: f64, col: [f64; 3]| {
            let n = ((norm(sub(to, from)) / (0.1 * d)).ceil() as usize).max(1);
            for i in 0..=n {
                draw(add(from, scale(sub(to, from), i as f64 / n as f64)), d, col);
            }
        };
        let (shortest, longest) = (len.iter().copied().fold(f64::INFINITY, f64::min), len.iter().copied().fold(0.0, f64::max));
        if let Some(diam) = self.box_diam {
            let corner = |i: usize| -> Vec3 { std::array::from_fn(|k| if i >> k & 1 == 1 { hi[k] } else { lo[k] }) };
            for i in 0..8 {
                for k in 0..3 {
                    if i >> k & 1 == 0 {
                        line(corner(i), corner(i | 1 << k), diam * shortest, self.box_color);
                    }
                }
            }
        }
        if let Some([length, diam]) = self.axes {
            for (k, col) in ["red", "green", "blue"].iter().enumerate() {
                let mut to = lo;
                to[k] += length * longest;
                line(lo, to, diam * shortest, rgb(col));
            }
        }
        image.iter().flat_map(|c| c.map(|v| (v * 255.0).round() as u8)).collect()
    }

    fn write_frame(&mut self, f: &Frame) -> Result<(), String> {
        let sys = f.sys;
        let step = sys.clock.step;
        self.head.every.wrote(step);
        let row = |i: usize, b: &mut Vec<f64>| {
            let r = sys.store.r[i];
            b.extend([sys.store.tag[i] as f64, r[0], r[1], r[2], f64::from(sys.store.kind[i])]);
        };
        let mut spheres = Vec::new();
        self.head.rows(f.sim, sys, 5, row, &mut |rows: &[f64]| -> Result<(), String> {
            for r in rows.chunks_exact(5) {
                let t = r[4] as u64;
                spheres.push(([r[1], r[2], r[3]], self.type_diameter(t), self.type_color(t)));
            }
            Ok(())
        })?;
        if sys.comm.rank() != 0 {
            return Ok(());
        }
        let pixels = self.render(sys.domain.lo, sys.domain.hi, &spheres);
        let path = self.head.path(step);
        let io = |e: String| format!("writing '{path}': {e}");
        let file = File::create(&path).map_err(|e| io(e.to_string()))?;
        let mut enc = png::Encoder::new(BufWriter::new(file), self.width as u32, self.height as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().map_err(|e| io(e.to_string()))?;
        w.write_image_data(&pixels).map_err(|e| io(e.to_string()))?;
        w.finish().map_err(|e| io(e.to_string()))
    }
}

fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale(a: Vec3, s: f64) -> Vec3 {
    a.map(|x| x * s)
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

fn unit(a: Vec3) -> Vec3 {
    scale(a, 1.0 / norm(a))
}

impl RunOutput for ImageDump {
    fn next_step(&self, step: u64, run: Span) -> Option<u64> {
        self.head.every.next_step(step, run)
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        self.write_frame(f).map_err(|e| format!("dump {}: {e}", self.head.id))
    }
}

impl Dump for ImageDump {
    fn modify(&mut self, key: &str, a: &mut Args) -> Result<(), ScriptError> {
        if self.head.modify(key, a)? {
            return Ok(());
        }
        match key {
            "acolor" => {
                let types = a.range("an atom type", u64::from(u32::MAX))?;
                let c = color(a, a.peek().unwrap_or(""))?;
                a.word("a color name")?;
                self.colors.push((types, c));
            }
            "adiam" => {
                let types = a.range("an atom type", u64::from(u32::MAX))?;
                self.diameters.push((types, a.positive("an atom diameter")?));
            }
            "region" => self.head.set_region(a)?,
            "backcolor" | "boxcolor" => {
                let c = color(a, a.peek().unwrap_or(""))?;
                a.word("a color name")?;
                *(if key == "backcolor" { &mut self.background } else { &mut self.box_color }) = c;
            }
            _ => return Err(unknown_key(&self.head, key, "acolor, adiam, backcolor, boxcolor, region", a)),
        }
        Ok(())
    }

    fn head(&self) -> &Head {
        &self.head
    }

    fn head_mut(&mut self) -> &mut Head {
        &mut self.head
    }
}
