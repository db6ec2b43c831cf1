"""The raps Python binding and the libraps it loads, both shipped inside the add-on.

The zip that `cmake --build build --target raps-blender-addon` makes holds the binding as the
package raps_uv.raps and the library as raps_uv/libraps.so. The binding loads $RAPS_LIBRARY
when set; it is pointed at the bundled library only while it loads, so that another raps the
user has (a pipeline's RAPS_LIBRARY) is neither used by the add-on nor changed for the rest of
Blender's process.
"""

import os

_BUNDLED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "libraps.so")


def _import_binding():
    before = os.environ.get("RAPS_LIBRARY")
    os.environ["RAPS_LIBRARY"] = _BUNDLED
    try:
        from . import raps as binding
    finally:
        if before is None:
            del os.environ["RAPS_LIBRARY"]
        else:
            os.environ["RAPS_LIBRARY"] = before
    return binding


raps = _import_binding()
