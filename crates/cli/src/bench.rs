pub struct BenchOptions {
    pub json: bool,
    pub quick: bool,
}
pub fn run(_o: &BenchOptions) -> anyhow::Result<()> {
    anyhow::bail!("bench not built yet")
}
