#!/usr/bin/python3
"""Tests of bindings/generate.py: it follows the header as it grows, and refuses what it does
not understand instead of dropping it (run by CTest as bindings_generator)."""

import os
import re
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import generate  # noqa: E402

with open(generate.HEADER, encoding="utf-8") as _stream:
    HEADER = _stream.read()


def replaced(old, new):
    assert old in HEADER, old
    return HEADER.replace(old, new, 1)


# The header's code with every comment blanked to spaces (newlines kept), so that offsets in it
# are offsets in HEADER and a brace or name inside a comment is never matched.
CODE = re.sub(r"/\*.*?\*/|//[^\n]*", lambda m: re.sub(r"[^\n]", " ", m.group()), HEADER,
              flags=re.DOTALL)
MODEL = generate.parse(HEADER)


def with_enum_member(member, name):
    """(HEADER with `name` appended as the last member of the enum block holding `member`, the
    value given). The value is the block's largest plus one, as the header appends them; the
    block and its last member are found in the text, so the header may grow around them."""
    assert name not in HEADER, "%s already exists: choose another name for the test" % name
    values = {constant.name: constant.value for constant in MODEL.constants}
    group = next(names for _, names in MODEL.enum_groups if member in names)
    value = max(values[other] for other in group) + 1
    for block in re.finditer(r"\benum\s*\{([^}]*)\}", CODE):
        if re.search(r"\b%s\b" % member, block.group(1)):
            body = block.group(1).rstrip()
            end = block.start(1) + len(body)  # just after the last member (or its comma)
            template = "\n    %s = %d," if body.endswith(",") else ",\n    %s = %d"
            addition = template % (name, value)
            return HEADER[:end] + addition + HEADER[end:], value
    raise AssertionError("no enum block holds %s" % member)


def with_struct_field(struct, declaration):
    """HEADER with the field `declaration` appended after the last field of `struct`."""
    match = re.search(r"\btypedef struct %s \{[^}]*\n(\}\s*%s\s*;)" % (struct, struct), CODE)
    assert match, "no 'typedef struct %s {...} %s;' in raps.h" % (struct, struct)
    return HEADER[:match.start(1)] + "    " + declaration + "\n" + HEADER[match.start(1):]


class Growth(unittest.TestCase):
    """The changes the sphere and atlas branches make must flow into all three bindings."""

    def test_current_header_has_every_function(self):
        header = generate.parse(HEADER)
        # An independent count: every "RAPS_API ... raps_x(" outside comments and #defines.
        code = re.sub(r"/\*.*?\*/|//[^\n]*", " ", HEADER, flags=re.DOTALL)
        code = re.sub(r"^#.*$", " ", code, flags=re.MULTILINE)
        declared = re.findall(r"RAPS_API[^;(]*?\b(raps_\w+)\s*\(", code)
        self.assertEqual([f.name for f in header.functions], declared)
        self.assertGreaterEqual(len(declared), 30)

    def test_appended_enum_constant(self):
        text, value = with_enum_member("RAPS_DOMAIN_DISK", "RAPS_DOMAIN_CYLINDER")
        # Appended to the domain block, after its current last member.
        group = next(names for _, names in generate.parse(text).enum_groups
                     if "RAPS_DOMAIN_DISK" in names)
        self.assertEqual(group[-1], "RAPS_DOMAIN_CYLINDER")
        files = generate.generate(text)
        self.assertIn("public const int RAPS_DOMAIN_CYLINDER = %d;" % value, files["csharp"])
        self.assertIn("pub const RAPS_DOMAIN_CYLINDER: i32 = %d;" % value, files["rust"])
        self.assertIn("\nRAPS_DOMAIN_CYLINDER = %d\n" % value, files["python"])

    def test_new_function_spanning_lines(self):
        text = replaced("#ifdef __cplusplus\n}", "/* Copies seams. */\nRAPS_API raps_status "
                        "raps_result_copy_seams(const raps_result* result,\n"
                        "                       uint32_t* dst, size_t capacity);\n\n"
                        "#ifdef __cplusplus\n}")
        files = generate.generate(text)
        self.assertIn("public static extern int raps_result_copy_seams(ResultHandle result, "
                      "[Out] uint[] dst, UIntPtr capacity);", files["csharp"])
        self.assertIn("pub fn raps_result_copy_seams(result: *const raps_result, dst: *mut u32, "
                      "capacity: usize) -> raps_status;", files["rust"])
        self.assertIn("'raps_result_copy_seams': (raps_status, [ctypes.POINTER(raps_result), "
                      "ctypes.POINTER(ctypes.c_uint32), ctypes.c_size_t]),", files["python"])
        self.assertIn("/// Copies seams.", files["rust"])

    def test_appended_stats_field(self):
        text = with_struct_field("raps_stats", "uint64_t seam_count; /* seams */")
        fields, _ = generate.parse(text).structs["raps_stats"]
        self.assertEqual(fields[-1].name, "seam_count")
        files = generate.generate(text)
        self.assertIn("public ulong SeamCount;", files["csharp"])
        self.assertIn("pub seam_count: u64,", files["rust"])
        self.assertIn("('seam_count', ctypes.c_uint64),", files["python"])

    def test_new_opaque_handle_gets_a_safe_handle(self):
        text = replaced("typedef struct raps_result raps_result;",
                        "typedef struct raps_result raps_result;\n"
                        "typedef struct raps_atlas raps_atlas;\n"
                        "RAPS_API void raps_atlas_destroy(raps_atlas* atlas);")
        files = generate.generate(text)
        self.assertIn("public sealed class AtlasHandle : SafeHandle", files["csharp"])
        self.assertIn("Native.raps_atlas_destroy(handle);", files["csharp"])
        self.assertIn("pub struct raps_atlas {", files["rust"])


class Refusals(unittest.TestCase):
    """Anything outside the header's controlled style stops the generator, naming the line."""

    def refused(self, text, words):
        with self.assertRaises(generate.HeaderError) as caught:
            generate.generate(text)
        for word in words:
            self.assertIn(word, str(caught.exception))

    def add_before_end(self, declaration):
        return replaced("#ifdef __cplusplus\n}", declaration + "\n\n#ifdef __cplusplus\n}")

    def test_unknown_types(self):
        self.refused(self.add_before_end("RAPS_API int raps_bad(void);"), ["int"])
        self.refused(self.add_before_end("RAPS_API raps_status raps_bad(bool x);"), ["bool"])
        self.refused(self.add_before_end("RAPS_API raps_status raps_bad(long x);"), ["long"])

    def test_unsupported_constructs(self):
        self.refused(self.add_before_end("RAPS_API raps_status raps_bad(const char* f, ...);"),
                     ["'.'"])
        self.refused(self.add_before_end("typedef union raps_u { int32_t a; } raps_u;"),
                     ["typedef"])
        self.refused(self.add_before_end("RAPS_API raps_status raps_bad(float xyz[3]);"),
                     ["'['"])
        self.refused(self.add_before_end("RAPS_API raps_status raps_bad();"), ["(void)"])
        self.refused(self.add_before_end("enum { RAPS_X };"), ["explicit value"])
        self.refused(self.add_before_end("static inline int32_t raps_helper(void) { return 1; }"),
                     ["raps.h:"])
        self.refused(self.add_before_end("#define RAPS_NAME \"raps\""), ["RAPS_NAME"])
        self.refused(self.add_before_end("#include <stdbool.h>"), ["stdbool"])

    def test_unmappable_parameter(self):
        # A pointer to a handle pointer that is not an out_ parameter has no safe mapping.
        self.refused(self.add_before_end(
            "RAPS_API raps_status raps_bad(raps_mesh** meshes);"), ["raps_bad", "meshes"])

    def test_handle_without_destroy(self):
        self.refused(replaced("typedef struct raps_result raps_result;",
                              "typedef struct raps_result raps_result;\n"
                              "typedef struct raps_atlas raps_atlas;"), ["raps_atlas_destroy"])

    def test_struct_with_pointer_field(self):
        self.refused(with_struct_field("raps_stats", "const float* data;"), ["data"])


class Command(unittest.TestCase):
    def test_check_reports_a_stale_file_with_a_diff(self):
        # Files written from raps.h, then checked against a header that has grown since: the
        # committed files are stale, and --check must fail and show what is missing.
        grown, value = with_enum_member("RAPS_DOMAIN_DISK", "RAPS_DOMAIN_CYLINDER")
        self.assertNotEqual(grown, HEADER)
        with tempfile.TemporaryDirectory() as root:
            header = os.path.join(root, "raps.h")
            with open(header, "w", encoding="utf-8") as stream:
                stream.write(grown)
            for relative in generate.OUTPUTS.values():
                os.makedirs(os.path.dirname(os.path.join(root, relative)), exist_ok=True)
            script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "generate.py")
            subprocess.run([sys.executable, script, "--root", root], check=True)

            def check(*extra):
                return subprocess.run([sys.executable, script, "--root", root, "--check"] +
                                      list(extra), stdout=subprocess.PIPE,
                                      stderr=subprocess.PIPE, universal_newlines=True)

            # The files match the header they were written from...
            self.assertEqual(check().returncode, 0)
            # ...and not the grown one.
            stale = check("--header", header)
            self.assertEqual(stale.returncode, 1)
            self.assertIn("+RAPS_DOMAIN_CYLINDER = %d" % value, stale.stdout)
            self.assertIn("do not match include/raps.h", stale.stderr)


if __name__ == "__main__":
    unittest.main()
