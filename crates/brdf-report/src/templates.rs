//! The compiled-in `minijinja` templates (HTML auto-escaping on).

use minijinja::Environment;

use crate::ReportError;

fn env() -> Result<Environment<'static>, ReportError> {
    let mut env = Environment::new();
    env.add_template("base.css", include_str!("../templates/base.css"))?;
    env.add_template("fit.html", include_str!("../templates/fit.html"))?;
    env.add_template("index.html", include_str!("../templates/index.html"))?;
    Ok(env)
}

/// Render template `name` with `ctx`.
pub fn render(name: &str, ctx: minijinja::Value) -> Result<String, ReportError> {
    Ok(env()?.get_template(name)?.render(ctx)?)
}
