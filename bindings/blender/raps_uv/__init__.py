"""raps for Blender: UV > Unwrap with raps and UV > Lightmap with raps.

The r-adaptive atlas of libraps (charts, a map per chart whose distortion is evened out, one
packed atlas) for the selected mesh objects, into the UV map the user names. The add-on ships
the raps Python binding and libraps.so (bindings/blender/CMakeLists.txt builds the zip).
"""

bl_info = {
    "name": "raps UV",
    "author": "raps",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D Viewport > UV (edit mode), Object > UV",
    "description": "Unwrap and lightmap uvs with raps, the r-adaptive parameterization",
    "category": "UV",
}

if "bpy" in locals():  # a reload from Blender's add-on preferences
    import importlib
    importlib.reload(mesh_io)  # noqa: F821
    importlib.reload(unwrap)  # noqa: F821
    importlib.reload(operators)  # noqa: F821

import bpy

from . import mesh_io, operators, unwrap  # noqa: E402,F401


class RAPS_MT_object_uv(bpy.types.Menu):
    """UV entries in object mode (Blender's own UV menu is edit mode's)"""
    bl_idname = "RAPS_MT_object_uv"
    bl_label = "UV"

    def draw(self, _context):
        _menu_entries(self, _context)


def _menu_entries(menu, _context):
    menu.layout.separator()
    menu.layout.operator(operators.RAPS_OT_unwrap.bl_idname)
    menu.layout.operator(operators.RAPS_OT_lightmap.bl_idname)


def _object_menu(menu, _context):
    menu.layout.menu(RAPS_MT_object_uv.bl_idname)


def register():
    for cls in operators.CLASSES + (RAPS_MT_object_uv,):
        bpy.utils.register_class(cls)
    bpy.types.VIEW3D_MT_uv_map.append(_menu_entries)
    bpy.types.VIEW3D_MT_object.append(_object_menu)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(_object_menu)
    bpy.types.VIEW3D_MT_uv_map.remove(_menu_entries)
    for cls in reversed(operators.CLASSES + (RAPS_MT_object_uv,)):
        bpy.utils.unregister_class(cls)
