//! Renders docs/fmu.md to the FMU's documentation/index.html (tables, code blocks) with pulldown-cmark: `cargo run --release -p ecf-fmu --example render_doc -- IN.md OUT.html`.

use pulldown_cmark::{html, Options, Parser};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(input), Some(output)) = (args.get(1), args.get(2)) else {
        eprintln!("usage: render_doc IN.md OUT.html");
        std::process::exit(2);
    };
    let text = match std::fs::read_to_string(input) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("render_doc: cannot read {input}: {e}");
            std::process::exit(1);
        }
    };
    let mut body = String::new();
    html::push_html(
        &mut body,
        Parser::new_ext(
            &text,
            Options::ENABLE_TABLES | Options::ENABLE_STRIKETHROUGH,
        ),
    );
    let page = format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>ecf_contact FMU</title>\n\
         <style>body{{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.4}}\
         table{{border-collapse:collapse}}td,th{{border:1px solid #bbb;padding:2px 6px}}\
         pre{{background:#f4f4f4;padding:0.6em;overflow-x:auto}}code{{font-size:0.95em}}</style>\n\
         </head><body>\n{body}</body></html>\n"
    );
    if let Err(e) = std::fs::write(output, page) {
        eprintln!("render_doc: cannot write {output}: {e}");
        std::process::exit(1);
    }
}
