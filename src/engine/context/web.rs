//! The browser: the page's canvas with a WebGL2 context (what OpenGL ES 3.0 is on the web),
//! under winit's web backend, which supplies the keys and the frame loop
//! (`requestAnimationFrame`). The page's address stands in for the command line, and the
//! page's title tells a script when the first frame is there (`ready`) or what went wrong
//! (`error: …`).

use std::rc::Rc;

use wasm_bindgen::JsCast;
use web_sys::{HtmlCanvasElement, WebGl2RenderingContext};
use winit::dpi::PhysicalSize;
use winit::event_loop::ActiveEventLoop;
use winit::platform::web::{WindowAttributesExtWebSys, WindowExtWebSys};
use winit::window::{Window, WindowAttributes};

use super::super::render_target::read_rgba8;
use super::super::Gl;
use super::platform::WindowApi;
use crate::error::{Error, Result};

/// The id of the page's canvas (`web/index.html`); without one, winit appends its own.
const CANVAS_ID: &str = "shadowmap";

fn document() -> Result<web_sys::Document> {
    web_sys::window()
        .and_then(|w| w.document())
        .ok_or_else(|| Error::Context("no document: not running in a page".into()))
}

/// The page's canvas window with its WebGL2 context, in the desktop window's shape.
pub struct WindowContext {
    gl: Gl,
    window: Window,
}

impl WindowContext {
    /// The page's canvas as the window, its WebGL2 context current (WebGL has no other).
    /// `--gl-api` other than auto is refused: the browser has only WebGL2.
    pub fn new(
        event_loop: &ActiveEventLoop,
        attributes: WindowAttributes,
        api: WindowApi,
    ) -> Result<WindowContext> {
        api.check(super::platform::Platform::Web)?;
        let canvas = document()?
            .get_element_by_id(CANVAS_ID)
            .and_then(|e| e.dyn_into::<HtmlCanvasElement>().ok());
        // The drawing buffer gets the asked size (the page's canvas says 1280 x 720).
        if let (Some(canvas), Some(size)) = (&canvas, attributes.inner_size) {
            let PhysicalSize { width, height } = size.to_physical::<u32>(1.0);
            canvas.set_width(width);
            canvas.set_height(height);
        }
        let append = canvas.is_none();
        let attributes = attributes
            .with_canvas(canvas)
            .with_append(append)
            .with_prevent_default(true)
            .with_focusable(true);
        let window = event_loop
            .create_window(attributes)
            .map_err(|e| Error::Context(format!("could not open the canvas: {e}")))?;
        let canvas = window
            .canvas()
            .ok_or_else(|| Error::Context("the window has no canvas".into()))?;
        let _ = canvas.focus();
        let gl = webgl2(&canvas)?;
        Ok(WindowContext {
            gl: Rc::new(super::super::bindings::GlContext::new(gl)),
            window,
        })
    }

    pub fn gl(&self) -> &Gl {
        &self.gl
    }

    /// The API and the window system, as the desktop reports them.
    pub fn api(&self) -> String {
        "WebGL2 in the browser".to_string()
    }

    pub fn window(&self) -> &Window {
        &self.window
    }

    /// The canvas's drawing-buffer size in pixels.
    pub fn framebuffer_size(&self) -> (u32, u32) {
        match self.window.canvas() {
            Some(c) => (c.width(), c.height()),
            None => (0, 0),
        }
    }

    /// The canvas follows the window's size by itself (winit sets it).
    pub fn resize(&self, _width: u32, _height: u32) {}

    /// Reads the drawing buffer, rows top to bottom (it is kept: `preserveDrawingBuffer`).
    pub fn read_back_buffer(&self) -> Vec<u8> {
        let (w, h) = self.framebuffer_size();
        read_rgba8(&self.gl, None, 0, w, h)
    }

    /// The browser shows the canvas when the frame's task ends: nothing to swap. The first
    /// frame there makes the page's title `ready`.
    pub fn swap_buffers(&self) -> Result<()> {
        if let Ok(doc) = document() {
            if doc.title() != "ready" && !doc.title().starts_with("error") {
                doc.set_title("ready");
            }
        }
        Ok(())
    }

    /// Binds the canvas's framebuffer for the main pass.
    pub fn bind_default_framebuffer(&self) {
        use glow::HasContext;
        unsafe { self.gl.bind_framebuffer(glow::FRAMEBUFFER, None) };
    }
}

/// The canvas's WebGL2 context: a depth and stencil buffer, no multisampling (the desktop's
/// config), the drawing buffer kept so that a script can read the picture after the frame.
fn webgl2(canvas: &HtmlCanvasElement) -> Result<glow::Context> {
    let options = js_options(&[
        ("antialias", false),
        ("depth", true),
        ("stencil", true),
        ("alpha", false),
        ("preserveDrawingBuffer", true),
    ]);
    let context = canvas
        .get_context_with_context_options("webgl2", &options)
        .ok()
        .flatten()
        .and_then(|c| c.dyn_into::<WebGl2RenderingContext>().ok())
        .ok_or_else(|| Error::Context("this browser gives the canvas no WebGL2 context".into()))?;
    let mut gl = glow::Context::from_webgl2_context(context);
    // WebGL has no KHR_debug: this finds none and installs nothing.
    super::super::check::install_debug_output(&mut gl, false);
    Ok(gl)
}

/// A plain JavaScript object of booleans (WebGL's context attributes).
fn js_options(pairs: &[(&str, bool)]) -> wasm_bindgen::JsValue {
    let object = js_sys::Object::new();
    for (key, value) in pairs {
        let _ = js_sys::Reflect::set(&object, &(*key).into(), &(*value).into());
    }
    object.into()
}

/// No context without a page to draw on: the browser's commands are the demo's.
pub(super) struct Backing;

impl Backing {
    pub(super) fn new(_debug: bool) -> Result<(Backing, Gl, String)> {
        Err(Error::Context(
            "the browser draws in the page's canvas only: no headless rendering here".into(),
        ))
    }

    pub(super) fn release(&self) {}
}

/// The page's address as the command line: `?scene=dummy&step=pcf&size=800x450&still=1&hud=0`
/// is `shadowmap demo --scene dummy --step pcf --size 800x450 --no-animation --no-hud`, so
/// that a bad name gets the command line's own message; `&view=visibility` is
/// `--show-visibility` (other views are the scene's cameras, `--view NAME`). Other keys pass as `--key value`
/// (`--key` alone without a value).
pub fn args() -> Vec<String> {
    let mut args = vec!["shadowmap".to_string(), "demo".to_string()];
    let search = web_sys::window()
        .and_then(|w| w.location().search().ok())
        .unwrap_or_default();
    let Ok(params) = web_sys::UrlSearchParams::new_with_str(&search) else {
        return args;
    };
    for entry in js_sys::try_iter(&params)
        .ok()
        .flatten()
        .into_iter()
        .flatten()
    {
        let Ok(pair) = entry.map(|e| js_sys::Array::from(&e)) else {
            continue;
        };
        let (key, value) = (
            pair.get(0).as_string().unwrap_or_default(),
            pair.get(1).as_string().unwrap_or_default(),
        );
        match (key.as_str(), value.as_str()) {
            ("still", "1") => args.push("--no-animation".into()),
            ("hud", "0") => args.push("--no-hud".into()),
            ("view", "visibility") => args.push("--show-visibility".into()),
            ("still" | "hud", _) => {}
            // `&show-depth-map` (no value): a flag.
            (_, "") => args.push(format!("--{key}")),
            _ => args.extend([format!("--{key}"), value]),
        }
    }
    args
}

/// Shows a panic's message on the page as an error, so that a page never stays blank
/// without a word (the browser's console would be the only other place).
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        report_error(&format!("internal error: {info} (please report this)"));
    }));
}

/// Shows an error on the page (and in its title, for scripts): the browser has no terminal.
pub fn report_error(message: &str) {
    let Ok(doc) = document() else {
        return;
    };
    doc.set_title(&format!("error: {message}"));
    if let Some(element) = doc.get_element_by_id("error") {
        element.set_text_content(Some(message));
    }
}

/// Shows what a key could not do on the page (the title stays: the demo goes on).
pub fn report_note(message: &str) {
    if let Some(element) = document().ok().and_then(|d| d.get_element_by_id("error")) {
        element.set_text_content(Some(&format!("note: {message}")));
    }
}
