//! The text `write_data` writes: header, Masses, pair coefficients, Atoms and Velocities.

use super::*;

/// The text of a data file, or why `data` cannot be written faithfully.
pub(super) fn render(data: &DataFile, style: AtomStyle) -> Result<String, String> {
    if data.natoms != data.atoms.len() {
        return Err(format!(
            "natoms is {} but there are {} atoms",
            data.natoms,
            data.atoms.len()
        ));
    }
    if data.ntypes != data.masses.len() {
        return Err(format!(
            "ntypes is {} but there are {} mass entries",
            data.ntypes,
            data.masses.len()
        ));
    }
    let given = data.masses.iter().filter(|m| m.is_some()).count();
    if given != 0 && given != data.masses.len() {
        return Err(format!(
            "masses are set for only {given} of {} atom types",
            data.masses.len()
        ));
    }
    if let Some(v) = &data.velocities {
        if v.len() != data.natoms {
            return Err(format!("{} velocities for {} atoms", v.len(), data.natoms));
        }
    }
    let finite = |what: &str, x: f64| {
        if x.is_finite() {
            Ok(x)
        } else {
            Err(format!("{what} is not finite: {x}"))
        }
    };

    let mut out = String::new();
    let title = data.title.replace(['\n', '\r'], " ");
    // `write!` to a String cannot fail.
    let _ = writeln!(out, "{}\n", title.trim());
    let _ = writeln!(out, "{} atoms", data.natoms);
    let _ = writeln!(out, "{} atom types\n", data.ntypes);
    for (d, (lo_name, hi_name)) in [("xlo", "xhi"), ("ylo", "yhi"), ("zlo", "zhi")]
        .into_iter()
        .enumerate()
    {
        let lo = finite(lo_name, data.lo[d])?;
        let hi = finite(hi_name, data.hi[d])?;
        let _ = writeln!(out, "{lo:?} {hi:?} {lo_name} {hi_name}");
    }
    if given != 0 {
        out.push_str("\nMasses\n\n");
        for (i, m) in data.masses.iter().enumerate() {
            let m = finite("mass", m.unwrap_or(f64::NAN))?;
            let _ = writeln!(out, "{} {m:?}", i + 1);
        }
    }
    if let Some(p) = &data.pair_coeffs {
        let name = if p.ij { "PairIJ Coeffs" } else { "Pair Coeffs" };
        let rows = if p.ij { data.ntypes * (data.ntypes + 1) / 2 } else { data.ntypes };
        if p.rows.len() != rows {
            return Err(format!("{name} has {} lines for {} atom types (expected {rows})", p.rows.len(), data.ntypes));
        }
        match &p.style {
            Some(style) => {
                let _ = writeln!(out, "\n{name} # {style}\n");
            }
            None => {
                let _ = writeln!(out, "\n{name}\n");
            }
        }
        for row in &p.rows {
            let _ = writeln!(out, "{}", row.join(" "));
        }
    }
    let _ = writeln!(out, "\nAtoms # {}\n", style.name());
    for a in &data.atoms {
        let _ = write!(out, "{} {}", a.tag, a.kind);
        if style == AtomStyle::Dpd {
            let Some(theta) = a.theta else {
                return Err(format!("atom {} has no dpdTheta", a.tag));
            };
            let _ = write!(out, " {:?}", finite("dpdTheta", theta)?);
        }
        if style == AtomStyle::Mdpd {
            out.push_str(" 0.0");
        }
        if style == AtomStyle::Edpd {
            let Some([t, cv]) = a.edpd else {
                return Err(format!("atom {} has no edpd_temp and edpd_cv", a.tag));
            };
            let _ = write!(out, " {:?} {:?}", finite("edpd_temp", t)?, finite("edpd_cv", cv)?);
        }
        if style == AtomStyle::Sph {
            let Some(rho) = a.sph_rho else {
                return Err(format!("atom {} has no rho", a.tag));
            };
            let _ = write!(out, " {:?} 0.0 1.0", finite("rho", rho)?);
        }
        for x in a.r {
            let _ = write!(out, " {:?}", finite("position", x)?);
        }
        let [ix, iy, iz] = a.image;
        let _ = writeln!(out, " {ix} {iy} {iz}");
    }
    // Written even when empty, so that `Some(vec![])` reads back as itself.
    if let Some(velocities) = &data.velocities {
        out.push_str("\nVelocities\n\n");
        for (tag, v) in velocities {
            let _ = write!(out, "{tag}");
            for x in v {
                let _ = write!(out, " {:?}", finite("velocity", *x)?);
            }
            out.push('\n');
        }
    }
    Ok(out)
}
