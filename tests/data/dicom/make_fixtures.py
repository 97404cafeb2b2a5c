#!/usr/bin/env python3
"""Writes the small synthetic DICOM fixtures of tests/data/dicom and the DICOM cases of the
invalid-input corpus (tests/data/invalid/invalid_*dicom*, ...), byte by byte (explicit VR little
endian, no library). Run once from this folder; the outputs are committed.

The real DICOM files (compressed transfer syntaxes, gantry tilt, multi-frame MR) are in
../shared/data/medical; these fixtures cover what those lack: per-frame functional groups with
per-frame rescale, a missing slice, two series in one folder, and broken headers."""
import os
import shutil
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
INVALID = os.path.join(HERE, "..", "invalid")
SEEDS = os.path.join(HERE, "..", "..", "fuzz", "corpus", "fuzz_dicom")
SHARED = os.path.join(HERE, "..", "..", "..", "..", "shared", "data", "medical")
SEPARATOR = b"\nOCTRACE-NEXT-FILE\n"  # fuzz_dicom's file separator
LONG_VRS = {"OB", "OW", "SQ", "UN", "UT", "UC", "UR"}
CT_IMAGE, ENHANCED_CT, MR_IMAGE = "1.2.840.10008.5.1.4.1.1.2", "1.2.840.10008.5.1.4.1.1.2.1", "1.2.840.10008.5.1.4.1.1.4"


def element(group, elem, vr, value):
    """One explicit-VR little-endian element; `value` is bytes, str, int (US, UL) or a list of items (SQ)."""
    if vr == "SQ":
        body = b"".join(struct.pack("<HHI", 0xFFFE, 0xE000, len(item)) + item for item in (dataset(i) for i in value))
    elif vr == "US":
        body = struct.pack("<H", value)
    elif vr == "UL" and isinstance(value, int):
        body = struct.pack("<I", value)
    elif isinstance(value, str):
        body = value.encode("ascii")
        if len(body) % 2:
            body += b"\0" if vr == "UI" else b" "
    else:
        body = value
    head = struct.pack("<HH", group, elem) + vr.encode("ascii")
    if vr in LONG_VRS:
        return head + b"\0\0" + struct.pack("<I", len(body)) + body
    return head + struct.pack("<H", len(body)) + body


def dataset(elements):
    """elements: {(group, elem): (vr, value)}, written in tag order as DICOM requires."""
    return b"".join(element(g, e, vr, v) for (g, e), (vr, v) in sorted(elements.items()))


def part10(elements, sop_class, transfer_syntax="1.2.840.10008.1.2.1"):
    meta_body = dataset({
        (0x0002, 0x0001): ("OB", b"\0\1"),
        (0x0002, 0x0002): ("UI", sop_class),
        (0x0002, 0x0003): ("UI", "1.2.826.0.1.3680043.9.7777.1"),
        (0x0002, 0x0010): ("UI", transfer_syntax),
    })
    meta = element(0x0002, 0x0000, "UL", len(meta_body)) + meta_body
    return b"\0" * 128 + b"DICM" + meta + dataset(elements)


def ds(*numbers):
    return "\\".join(repr(float(n)) if not isinstance(n, str) else n for n in numbers)


def image(series_uid, modality, rows, cols, pixels, frames=1, extra=None, description="", number=1):
    """A 16-bit signed image (frames x rows x cols values in `pixels`)."""
    e = {
        (0x0008, 0x0060): ("CS", modality),
        (0x0008, 0x103E): ("LO", description),
        (0x0020, 0x000E): ("UI", series_uid),
        (0x0020, 0x0011): ("IS", str(number)),
        (0x0028, 0x0002): ("US", 1),
        (0x0028, 0x0004): ("CS", "MONOCHROME2"),
        (0x0028, 0x0010): ("US", rows),
        (0x0028, 0x0011): ("US", cols),
        (0x0028, 0x0100): ("US", 16),
        (0x0028, 0x0101): ("US", 16),
        (0x0028, 0x0102): ("US", 15),
        (0x0028, 0x0103): ("US", 1),
        (0x7FE0, 0x0010): ("OW", struct.pack("<%dh" % len(pixels), *pixels)),
    }
    if frames > 1:
        e[(0x0028, 0x0008)] = ("IS", str(frames))
    e.update(extra or {})
    return e


def slice_at(series_uid, modality, rows, cols, z, value, **kw):
    """A single-frame axial slice at height z whose pixels are value + index."""
    extra = {
        (0x0020, 0x0032): ("DS", ds(-10, -20, z)),
        (0x0020, 0x0037): ("DS", ds(1, 0, 0, 0, 1, 0)),
        (0x0028, 0x0030): ("DS", ds(0.5, 0.5)),
    }
    extra.update(kw.pop("extra", {}))
    return image(series_uid, modality, rows, cols, [value + i for i in range(rows * cols)], extra=extra, **kw)


def enhanced_ct(positions, intercepts, spacing=ds(0.5, 0.25), rows=4, cols=4):
    """Enhanced CT: one frame per position; per-frame positions and rescale, shared spacing and orientation."""
    per_frame = [{
        (0x0020, 0x9113): ("SQ", [{(0x0020, 0x0032): ("DS", p)}]),
        (0x0028, 0x9145): ("SQ", [{(0x0028, 0x1052): ("DS", ds(b)), (0x0028, 0x1053): ("DS", ds(1))}]),
    } for p, b in zip(positions, intercepts)]
    shared = [{
        (0x0020, 0x9116): ("SQ", [{(0x0020, 0x0037): ("DS", ds(1, 0, 0, 0, 1, 0))}]),
        (0x0028, 0x9110): ("SQ", [{(0x0028, 0x0030): ("DS", spacing), (0x0018, 0x0050): ("DS", ds(2))}]),
    }]
    n = len(positions)
    pixels = [100 * f + i for f in range(n) for i in range(rows * cols)]
    extra = {(0x5200, 0x9229): ("SQ", shared), (0x5200, 0x9230): ("SQ", per_frame)}
    return image("1.2.826.0.1.3680043.9.7777.10", "CT", rows, cols, pixels, frames=n, extra=extra,
                 description="enhanced")


def write(path, elements, sop_class=CT_IMAGE):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(part10(elements, sop_class))


def fresh(folder):
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    return folder


def main():
    # Valid fixtures.
    # Frames stored from the top down (z = 4, 2, 0); each frame its own intercept.
    write(os.path.join(HERE, "enhanced_ct_3frames.dcm"),
          enhanced_ct([ds(-10, -20, 4), ds(-10, -20, 2), ds(-10, -20, 0)], [-1000, -1010, -1020]), ENHANCED_CT)
    # MR slices at z = 0, 2, 4, 8 (the one at 6 is missing); file names in another order.
    d = fresh(os.path.join(HERE, "missing_slice"))
    for name, z in [("a.dcm", 8), ("b.dcm", 0), ("c.dcm", 4), ("d.dcm", 2)]:
        write(os.path.join(d, name), slice_at("1.2.826.0.1.3680043.9.7777.20", "MR", 4, 4, z, int(z) * 10), MR_IMAGE)
    # Two series in one folder (a nested one): a small MR (series 1) and a larger CT (series 2).
    d = fresh(os.path.join(HERE, "two_series"))
    for k in range(2):
        write(os.path.join(d, "mr%d.dcm" % k),
              slice_at("1.2.826.0.1.3680043.9.7777.31", "MR", 4, 4, k, 0, description="small mr", number=1), MR_IMAGE)
    for k in range(3):
        write(os.path.join(d, "sub", "ct%d.dcm" % k),
              slice_at("1.2.826.0.1.3680043.9.7777.32", "CT", 6, 6, k, 0, description="large ct", number=2,
                       extra={(0x0028, 0x1052): ("DS", ds(-1024)), (0x0028, 0x1053): ("DS", ds(1))}))

    # Invalid corpus.
    d = fresh(os.path.join(INVALID, "invalid_no_dicom_images"))
    with open(os.path.join(d, "notes.txt"), "w") as f:
        f.write("not a DICOM file\n")
    write(os.path.join(d, "report.dcm"), {(0x0008, 0x0060): ("CS", "SR"), (0x0020, 0x000E): ("UI", "1.2.3")},
          "1.2.840.10008.5.1.4.1.1.88.11")
    write(os.path.join(INVALID, "invalid_not_an_image.dcm"),
          {(0x0008, 0x0060): ("CS", "SR"), (0x0020, 0x000E): ("UI", "1.2.3")}, "1.2.840.10008.5.1.4.1.1.88.11")
    d = fresh(os.path.join(INVALID, "invalid_mixed_sizes"))
    for k, rows in enumerate([4, 4, 5]):
        write(os.path.join(d, "s%d.dcm" % k), slice_at("1.2.826.0.1.3680043.9.7777.40", "CT", rows, 4, k, 0))
    # 100,000 frames of 64x64 declared over 8 KiB of pixel data.
    write(os.path.join(INVALID, "invalid_huge_frame_count.dcm"),
          image("1.2.826.0.1.3680043.9.7777.50", "MR", 64, 64, [0] * 4096, frames=100000), MR_IMAGE)
    write(os.path.join(INVALID, "invalid_zero_pixel_spacing.dcm"),
          enhanced_ct([ds(0, 0, 0), ds(0, 0, 1)], [0, 0], spacing=ds(0, 0.5)), ENHANCED_CT)
    write(os.path.join(INVALID, "invalid_nan_position.dcm"),
          enhanced_ct([ds(0, 0, 0), "NaN\\0\\1"], [0, 0]), ENHANCED_CT)

    # A single 4x4 CT image: not broken, but not a volume: render refuses it (a surface needs a
    # volume), slice draws it in its own plane.
    write(os.path.join(INVALID, "invalid_single_image.dcm"),
          slice_at("1.2.826.0.1.3680043.9.7777.90", "CT", 4, 4, 3, 0,
                   extra={(0x0028, 0x1052): ("DS", ds(-1024)), (0x0028, 0x1053): ("DS", ds(1))}))

    # Files on which GDCM (Debian builds it with assertions on) aborts the process; octrace's
    # own structure walk (io/src/DicomValidator.*) refuses them before GDCM opens them.
    # fuzz_dicom's first finding: two_series' sub/ct0.dcm whose RescaleIntercept (DS, 8 bytes
    # at the end of the header) declares 8,456 bytes; GDCM's retry hits assert(is.good()) in
    # FileMetaInformation::ReadCompat.
    ct0 = part10(slice_at("1.2.826.0.1.3680043.9.7777.32", "CT", 6, 6, 0, 0, description="large ct", number=2,
                          extra={(0x0028, 0x1052): ("DS", ds(-1024)), (0x0028, 0x1053): ("DS", ds(1))}), CT_IMAGE)
    at = ct0.index(struct.pack("<HH", 0x0028, 0x1052) + b"DS")
    assert struct.unpack("<H", ct0[at + 6:at + 8])[0] == 8
    with open(os.path.join(INVALID, "invalid_length_past_end.dcm"), "wb") as f:
        f.write(ct0[:at + 6] + struct.pack("<H", 8456) + ct0[at + 8:])
    # An MR slice whose PixelRepresentation has VR UI instead of US (found by fuzz_dicom):
    # gdcm::Attribute<0x0028,0x0103> asserts that the VRs are compatible while GDCM's image
    # reader reads it. Structurally sound: DicomFile refuses it with GDCM's dictionary.
    mr = slice_at("1.2.826.0.1.3680043.9.7777.80", "MR", 4, 4, 0, 0)
    mr[(0x0028, 0x0103)] = ("UI", struct.pack("<H", 1))
    write(os.path.join(INVALID, "invalid_vr_mismatch.dcm"), mr, MR_IMAGE)
    # An enhanced CT without any ImageOrientationPatient (found by fuzz_dicom): GDCM's image
    # reader computes the slice spacing from it and asserts "b1 && cosines.size() == 6".
    e = enhanced_ct([ds(0, 0, 0), ds(0, 0, 1)], [0, 0])
    e[(0x5200, 0x9229)] = ("SQ", [{(0x0028, 0x9110): ("SQ", [{(0x0028, 0x0030): ("DS", ds(0.5, 0.5))}])}])
    write(os.path.join(INVALID, "invalid_enhanced_without_orientation.dcm"), e, ENHANCED_CT)
    # The meta group and nothing after it (a truncation found by DicomValidatorTest): GDCM's
    # meta reader asserts "Should not happen" when no tag follows.
    with open(os.path.join(INVALID, "invalid_meta_group_only.dcm"), "wb") as f:
        f.write(part10({}, CT_IMAGE))
    # JPEG-compressed pixel data cut after the (empty) offset table, without the sequence
    # delimitation (a truncation found by DicomValidatorTest): GDCM makes up an empty
    # fragment and asserts "ValueField" while decoding.
    jpeg = image("1.2.826.0.1.3680043.9.7777.70", "MR", 4, 4, [0] * 16)
    jpeg.pop((0x7FE0, 0x0010))
    head = part10(jpeg, MR_IMAGE, "1.2.840.10008.1.2.4.50")
    with open(os.path.join(INVALID, "invalid_unterminated_fragments.dcm"), "wb") as f:
        f.write(head + struct.pack("<HH", 0x7FE0, 0x0010) + b"OB\0\0" + struct.pack("<I", 0xFFFFFFFF) +
                struct.pack("<HHI", 0xFFFE, 0xE000, 0))


def seeds():
    """Seeds of tests/fuzz/corpus/fuzz_dicom: the fixtures above (a folder's files joined by the
    separator), a small gantry-tilted stack, and the real single files under 16 KB. The folder
    also holds seeds written elsewhere (make_volume_corpus.py, octrace_write_dicom, fuzzing
    findings: docs/dev/fuzzing.md), so only these files are rewritten; nothing is removed."""
    out = SEEDS
    os.makedirs(out, exist_ok=True)
    def folder_bytes(folder):
        files = sorted(os.path.join(r, f) for r, _, fs in os.walk(folder) for f in fs if f.endswith(".dcm"))
        return SEPARATOR.join(open(f, "rb").read() for f in files[:4])
    for name in ["missing_slice", "two_series"]:
        open(os.path.join(out, name), "wb").write(folder_bytes(os.path.join(HERE, name)))
    for name in ["invalid_mixed_sizes"]:
        open(os.path.join(out, name), "wb").write(folder_bytes(os.path.join(INVALID, name)))
    for name in ["enhanced_ct_3frames.dcm"]:
        shutil.copy(os.path.join(HERE, name), out)
    for name in ["invalid_nan_position.dcm", "invalid_zero_pixel_spacing.dcm", "invalid_huge_frame_count.dcm",
                 "invalid_length_past_end.dcm", "invalid_meta_group_only.dcm", "invalid_unterminated_fragments.dcm", "invalid_vr_mismatch.dcm",
                 "invalid_enhanced_without_orientation.dcm", "invalid_jpeg_garbage_in_header.dcm"]:
        shutil.copy(os.path.join(INVALID, name), out)
    tilted = [part10(slice_at("1.2.826.0.1.3680043.9.7777.60", "CT", 4, 4, k, 0,
                              extra={(0x0020, 0x0032): ("DS", ds(-10, -20 + 0.25 * k, k))}), CT_IMAGE) for k in range(4)]
    open(os.path.join(out, "gantry_tilt"), "wb").write(SEPARATOR.join(tilted))
    for name in ["MR_small.dcm", "MR_small_bigendian.dcm", "JPEG-lossy.dcm"]:
        if os.path.exists(os.path.join(SHARED, name)):
            shutil.copyfile(os.path.join(SHARED, name), os.path.join(out, name))


if __name__ == "__main__":
    main()
    seeds()
