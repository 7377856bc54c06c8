#!/usr/bin/env python3
"""Builds LinkGI's documentation site into <build>/docs/html (open index.html there).

  /usr/bin/python3 scripts/docs.py [--build build]      (under an X server: Testing/run_with_xvfb.sh)

1. copies Documentation/ (the pages and conf.py) into <build>/docs/src;
2. generates the API reference there: the C++ classes from their headers' documentation
   (class descriptions and the `///@{ ... ///@}` property blocks, as VTK writes them) and the
   Python module `linkgi` from its docstrings (which VTK's wrapping makes from the same
   comments), so nothing is written twice;
3. runs every gallery example (GALLERY below) from the build, and puts its picture, its
   source and how to run it on a gallery page, with the date, machine and commit;
4. runs sphinx-build with warnings as errors.
Needs Debian's python3-sphinx, python3-myst-parser and python3-pydata-sphinx-theme
(scripts/setup.sh installs them) and a build with the examples and the ParaView plugin.
ctest runs it as docs.Site (README command 2).
"""
import argparse
import ast
import datetime
import inspect
import os
import platform
import re
import shutil
import subprocess
import sys

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The gallery: name, title, kind, method, what it shows, command ({out} is the picture,
# {build} the build directory, {top} the source tree), the source shown.
GALLERY = [
    ("five-minutes", "A sphere on a plane under a lamp", "VTK Python", "link structure",
     "The README's five minutes: vtkGlobalIlluminationFilter lights the surface, "
     "vtkGlobalIlluminationMapper draws it with shadow maps and the default look.",
     ["{python}", "{top}/Examples/Python/five_minutes.py", "{out}"],
     "Examples/Python/five_minutes.py"),
    ("cornell-demo", "The Cornell box (README command 1)", "C++", "link structure",
     "linkgi-demo: the Cornell box with its lamp, the direct light per pixel with shadow maps "
     "plus three bounces of per-vertex indirect light, in the default look.",
     ["{build}/bin/linkgi-demo", "{out}"], "Examples/Cxx/LinkGIDemo.cxx"),
    ("methods", "The four methods side by side", "VTK Python",
     "link structure, instant radiosity, implicit visibility, photon mapping",
     "The Cornell box lit by each method at its defaults, with the time of each update.",
     ["{python}", "{top}/Examples/Python/methods.py", "{out}"], "Examples/Python/methods.py"),
    ("surface-vs-global-illumination", "Surface and Global Illumination in ParaView",
     "ParaView (pvbatch)", "link structure",
     "An isosurface of the Wavelet coloured by elevation over a plane, the default light kit "
     "plus a directional light: the same colours as Surface, with shadows and bounced light.",
     ["{pvbatch}", "{top}/paraview-plugin/examples/surface_vs_global_illumination.py", "{out}"],
     "paraview-plugin/examples/surface_vs_global_illumination.py"),
    ("paraview-cornell", "A lamp in ParaView", "ParaView (pvbatch)", "link structure",
     "The Global Illumination Scene source's Cornell box with a Light Inspector point light "
     "made a lamp by Light Falloff, shown in the automatic look.",
     ["{pvbatch}", "{top}/paraview-plugin/examples/cornell_box.py", "{out}"],
     "paraview-plugin/examples/cornell_box.py"),
    ("refinement", "Refinement where the light changes", "VTK Python", "link structure",
     "A floor of two triangles and a box, left as given and right refined where the light "
     "changes fast.",
     ["{python}", "{top}/Examples/Python/refinement.py", "{out}"], "Examples/Python/refinement.py"),
    ("caustics", "Caustics under glass and a mirror", "VTK Python", "photon mapping",
     "The caustic scene: a glass ball and a mirror band over a floor, the direct, indirect "
     "and caustic irradiance on a log scale.",
     ["{python}", "{top}/Documentation/caustics-images.py", "{out}"],
     "Documentation/caustics-images.py"),
    ("export-page", "Shared as a web page", "VTK Python", "link structure",
     "The five-minute scene drawn by the mapper (shadows per pixel) and its page from "
     "linkgi.export_html in headless Chromium (the baked per-vertex colours, any browser).",
     ["{python}", "{top}/Documentation/export-images.py", "{out}"],
     "Documentation/export-images.py"),
    ("pyvista-nut", "In PyVista: a nut on a floor under a lamp", "PyVista", "link structure",
     "linkgi.pyvista.add_mesh takes plotter.add_mesh's arguments and draws the mesh with "
     "shadows and bounced light; left, PyVista's own rendering of the same scene.",
     ["{venv}", "{top}/Examples/Python/pyvista_nut.py", "{out}"],
     "Examples/Python/pyvista_nut.py"),
    ("implicit-visibility-errors", "Implicit visibility against the reference",
     "VTK Python", "implicit visibility",
     "The error of implicit visibility's indirect light against the path-traced reference.",
     ["{python}", "{top}/Documentation/implicit-visibility-errors.py", "{out}"],
     "Documentation/implicit-visibility-errors.py"),
]

CXX_HEADERS = [
    "Filters/GlobalIllumination/vtkGlobalIlluminationFilter.h",
    "Filters/GlobalIllumination/vtkGlobalIlluminationSceneSource.h",
    "Filters/GlobalIllumination/vtkGlobalIlluminationLights.h",
    "Filters/GlobalIllumination/vtkGlobalIlluminationColors.h",
    "Rendering/GlobalIllumination/vtkGlobalIlluminationMapper.h",
    "Rendering/GlobalIllumination/vtkGlobalIlluminationCompositeMapper.h",
    "Rendering/GlobalIllumination/vtkGlobalIlluminationShading.h",
    "Rendering/GlobalIllumination/vtkGlobalIlluminationAsyncWatcher.h",
    "Rendering/GlobalIllumination/vtkGlobalIlluminationDrawnAlbedo.h",
    "Rendering/GlobalIllumination/vtkGlobalIlluminationDisplayColors.h",
    "Rendering/GlobalIllumination/vtkGlobalIlluminationGlobalCasters.h",
]


def comment_text(block):
    """The text of a /** ... */ or /// comment, without the comment marks."""
    lines = []
    for line in block.splitlines():
        line = line.strip()
        line = re.sub(r"^(/\*\*|\*/|\*|///<|///|//)", "", line).rstrip("*/").strip() \
            if not line.startswith("*/") else ""
        lines.append(line)
    text = "\n".join(lines).strip()
    return re.sub(r"@(class|brief)\s+", "", text)


def prose(text):
    """A header comment as Markdown: its lists and `code` read as written; lines that
    Markdown would take for headings or rules are escaped."""
    lines = [("\\" + l) if re.match(r"\s*(#|={3,}|-{3,})", l) else l for l in text.splitlines()]
    return "\n".join(lines).strip() + "\n"


def fenced(text, language=""):
    return "```" + language + "\n" + text.rstrip() + "\n```\n"


def cxx_reference(path):
    """Markdown for one header: its class description and its documented members."""
    source = open(os.path.join(TOP, path), encoding="utf-8").read()
    name = os.path.splitext(os.path.basename(path))[0]
    head = re.match(r"\s*/\*\*(.*?)\*/", source, re.S)
    out = ["## " + name, "", "`" + path + "`", ""]
    if head:
        description = comment_text(head.group(1)).split("\n", 2)
        out += ["**" + description[1].strip() + "**" if len(description) > 1 else "", "",
                prose(description[2]) if len(description) > 2 else "", ""]
    body = source[head.end():] if head else source
    # Documented declarations: a /** */ or /// comment followed by code up to ';' or '{',
    # inside ///@{ ... ///@} groups as VTK writes its properties.
    for group in re.finditer(r"///@\{(.*?)///@\}", body, re.S):
        text = group.group(1)
        doc = re.search(r"/\*\*(.*?)\*/", text, re.S) or re.search(r"((?:\s*///[^\n]*\n)+)", text)
        code = text[doc.end():] if doc else text
        decls = "\n".join(l.rstrip() for l in code.strip().splitlines() if l.strip())
        out += [fenced(decls, "cpp"), "", prose(comment_text(doc.group(1))) if doc else "", ""]
    return "\n".join(out)


def python_reference():
    """Markdown for `import linkgi`: every class's docstring and its own methods'."""
    import linkgi
    out = ["# Python: `import linkgi`", "",
           "The classes VTK's wrapping makes of the C++ ones, in Debian's `/usr/bin/python3`; "
           "each docstring is the header's documentation.", ""]
    out += ["## linkgi.methods()", "", fenced(inspect.cleandoc(linkgi.methods.__doc__), "text"), ""]
    from linkgi import export
    out += ["## Sharing: `linkgi.bake`, `linkgi.export_html`, `linkgi.export_glb`", "",
            fenced(inspect.cleandoc(export.__doc__), "text"), ""]
    for function in (export.bake, export.export_html, export.export_glb):
        out += ["### linkgi." + function.__name__ + str(inspect.signature(function)), "",
                fenced(inspect.cleandoc(function.__doc__), "text"), ""]
    # linkgi.pyvista imports PyVista, which only build/venv has: read, not imported.
    source = ast.parse(open(os.path.join(TOP, "Wrapping", "Python", "linkgi", "pyvista.py"),
                            encoding="utf-8").read())
    out += ["## PyVista: `linkgi.pyvista`", "", fenced(ast.get_docstring(source), "text"), ""]
    for node in source.body:
        if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
            out += ["### linkgi.pyvista.%s(%s)" % (node.name, ast.unparse(node.args)), "",
                    fenced(ast.get_docstring(node), "text"), ""]
    from linkgi import web  # imports trame only when run
    out += ["## Live in the browser: `python -m linkgi.web`", "",
            fenced(inspect.cleandoc(web.__doc__), "text"), ""]
    for name in sorted(n for n in dir(linkgi) if n.startswith("vtk")):
        cls = getattr(linkgi, name)
        out += ["## linkgi." + name, "", fenced(inspect.cleandoc(cls.__doc__ or ""), "text"), ""]
        for method in sorted(cls.__dict__):
            member = cls.__dict__[method]
            if method.startswith("_") or not callable(member) or not member.__doc__:
                continue
            out += ["### " + name + "." + method, "", fenced(inspect.cleandoc(member.__doc__), "text"), ""]
    return "\n".join(out)


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def api_pages(src):
    write(os.path.join(src, "api", "index.md"), "\n".join([
        "# API reference", "",
        "Generated from the C++ headers' documentation and the Python docstrings, which VTK's "
        "wrapping makes from the same comments.", "",
        "```{toctree}", ":maxdepth: 1", "", "cxx", "python", "```", ""]))
    write(os.path.join(src, "api", "cxx.md"), "\n".join(
        ["# C++: LinkGI::FiltersGlobalIllumination and LinkGI::RenderingGlobalIllumination", "",
         "Each class's description, then each documented property or method with its "
         "declaration and what it does (defaults included).", ""] +
        [cxx_reference(h) for h in CXX_HEADERS]))
    write(os.path.join(src, "api", "python.md"), python_reference())


def gallery(src, build, environment, pv_environment):
    folder = os.path.join(src, "gallery")
    os.makedirs(folder, exist_ok=True)
    commit = subprocess.run(["git", "-C", TOP, "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    cpu = platform.processor() or platform.machine()
    for line in open("/proc/cpuinfo", encoding="utf-8", errors="replace"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    when = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    page = ["# Example gallery", "",
            "Every picture here was made by running the example shown under it, while this "
            "site was built: on %s, on %s (%d cores, Mesa's software OpenGL), at commit %s."
            % (when, cpu, os.cpu_count(), commit), ""]
    values = {"python": "/usr/bin/python3", "pvbatch": "pvbatch", "build": build, "top": TOP,
              "venv": os.path.join(build, "venv", "bin", "python")}
    for name, title, kind, method, what, command, shown in GALLERY:
        picture = os.path.join(folder, name + ".png")
        argv = [part.format(out=picture, **values) for part in command]
        result = subprocess.run(argv, capture_output=True, text=True, timeout=300,
                                env=pv_environment if command[0] == "{pvbatch}" else environment)
        if result.returncode != 0 or not os.path.isfile(picture):
            sys.stderr.write(result.stdout[-4000:] + result.stderr[-4000:])
            raise SystemExit("docs: the gallery example %s failed (%s); its picture comes "
                             "from running it" % (name, " ".join(argv)))
        copy = name + os.path.splitext(shown)[1]
        shutil.copy(os.path.join(TOP, shown), os.path.join(folder, copy))
        language = "cpp" if shown.endswith(".cxx") else "python"
        page += ["## " + title, "", "*%s, %s.* %s" % (kind, method, what), "",
                 "![%s](%s.png)" % (title, name), "",
                 "`%s`, run as" % shown, "",
                 fenced(" ".join(part.replace("{out}", name + ".png")
                                 .replace("{build}/", "build/").replace("{top}/", "")
                                 .replace("{python}", "/usr/bin/python3")
                                 .replace("{venv}", "build/venv/bin/python")
                                 .replace("{pvbatch}", "pvbatch") for part in command), "sh"),
                 "```{literalinclude} " + copy, ":language: " + language, "```", ""]
    write(os.path.join(folder, "index.md"), "\n".join(page))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    args = parser.parse_args()
    for module, package in (("sphinx", "python3-sphinx"), ("myst_parser", "python3-myst-parser"),
                            ("pydata_sphinx_theme", "python3-pydata-sphinx-theme")):
        try:
            __import__(module)
        except ImportError:
            raise SystemExit("docs: %s is missing; install %s (scripts/setup.sh does)"
                             % (module, package))
    build = os.path.abspath(args.build)
    plugin = os.path.join(build, "paraview-plugin", "lib", "paraview-5.11", "plugins", "LinkGI",
                          "LinkGI.so")
    if not os.path.isfile(plugin) or not os.path.isfile(os.path.join(build, "bin", "linkgi-demo")):
        raise SystemExit("docs: the gallery runs linkgi-demo and the ParaView plugin; build them "
                         "first (scripts/build.sh, with paraview-dev installed)")
    out = os.path.join(build, "docs")
    src = os.path.join(out, "src")
    shutil.rmtree(src, ignore_errors=True)
    shutil.copytree(os.path.join(TOP, "Documentation"), src)
    environment = dict(os.environ)
    # conf.py resolves the pages' links to files outside Documentation/ (records/) here.
    environment["LINKGI_DOCUMENTATION_SOURCE"] = os.path.join(TOP, "Documentation")
    python_path = [os.path.join(build, "lib", "python3.11", "dist-packages"),
                   os.path.join(build, "python3-paraview", "usr", "lib", "python3",
                                "dist-packages")]
    environment["PYTHONPATH"] = python_path[0]
    sys.path.insert(0, python_path[0])
    api_pages(src)
    # pvbatch needs ParaView's Python, and its plugin.
    pv_environment = dict(environment)
    pv_environment["PYTHONPATH"] = python_path[1]
    pv_environment["LINKGI_PLUGIN"] = plugin
    gallery(src, build, environment, pv_environment)
    html = os.path.join(out, "html")
    result = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b",
                             "html", "-d", os.path.join(out, "doctrees"), src, html],
                            env=environment)
    if result.returncode != 0:
        raise SystemExit("docs: sphinx-build reported warnings or errors (above)")
    print("docs: open %s" % os.path.join(html, "index.html"))


if __name__ == "__main__":
    main()
