# Sphinx configuration of LinkGI's documentation site. Built by scripts/docs.py (which
# copies Documentation/ into <build>/docs/src, generates the API reference and the gallery
# there, and runs sphinx-build -W); ctest runs it as docs.Site.
import os

project = "LinkGI"
author = "The LinkGI authors"
release = os.environ.get("LINKGI_VERSION", "")
version = release

extensions = ["myst_parser"]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
master_doc = "index"
myst_heading_anchors = 4
# Scripts and data files are linked from the pages, not pages themselves.
exclude_patterns = ["_build", "**/*.json", "**/*.jsonl", "**/*.log", "**/*.txt", "**/*.sh",
                    "**/*.py"]

html_theme = "pydata_sphinx_theme"  # PyVista's theme
html_title = "LinkGI"
html_theme_options = {
    "show_prev_next": True,
    "navigation_depth": 2,
}
html_static_path = []

# Documentation/ in the source tree: the site is built from a copy (scripts/docs.py), and the
# pages link to files beside it that the copy does not hold (the measurement records in
# records/, at the repository's top).
SOURCE = os.environ.get("LINKGI_DOCUMENTATION_SOURCE", os.path.dirname(os.path.abspath(__file__)))


def _link_into_the_source_tree(app, domain, node):
    """Links to a folder or a file of the source tree that is not a page (a script, the
    records in records/) are kept as text, without a warning; a link to a missing page or
    file still warns."""
    target = node.get("reftarget", "").split("#")[0]
    if not target:
        return None
    folder = os.path.dirname(node.get("refdoc", "index"))
    for top in (app.srcdir, SOURCE):
        path = os.path.normpath(os.path.join(top, folder, target))
        inside = path.startswith(os.path.normpath(top) + os.sep)
        if os.path.exists(path) and not (inside and path.endswith(".md")):
            return True
    return None


def setup(app):
    app.connect("warn-missing-reference", _link_into_the_source_tree)
