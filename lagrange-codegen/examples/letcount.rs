use syn::{File, Item};
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let src = std::fs::read_to_string(path).unwrap();
    let file: File = syn::parse_file(&src).unwrap();
    for item in file.items {
        if let Item::Struct(s) = item {
            if !s.attrs.iter().any(|a| a.path().is_ident("lagrange")) {
                continue;
            }
            let input: syn::DeriveInput = s.clone().into();
            let t0 = std::time::Instant::now();
            let out = lagrange_codegen::expand(&input).to_string();
            println!(
                "{}: {} bytes, {:.2} s",
                s.ident,
                out.len(),
                t0.elapsed().as_secs_f64()
            );
            for (i, chunk) in out.split(" fn ").enumerate().skip(1) {
                let name: String = chunk
                    .chars()
                    .take_while(|c| *c != '(' && *c != '<')
                    .collect();
                let lets = chunk.matches("let ").count();
                if lets > 500 {
                    println!("  fn {name}: {lets} lets, {} bytes", chunk.len());
                }
                let _ = i;
            }
        }
    }
}
