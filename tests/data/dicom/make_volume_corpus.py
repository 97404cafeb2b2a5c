#!/usr/bin/env python3
"""Writes the multi-volume cases of the invalid-input corpus (tests/data/invalid/invalid_volume*)
from real data: the slices of the Siemens XA10 resting-state fMRI as dcm2niix converted it
(../shared/data/medical/siemens_xa10_fmri_4d/reference_dcm2niix.nii, 64 x 64 x 6 x 4, int16),
written back as classic MR slices (one file per slice, explicit VR little endian, with
make_fixtures.py's byte writer) whose TemporalPositionIdentifier tells their time points apart,
at the positions the NIfTI's sform gives (RAS turned into DICOM's LPS). Two time points each:

- invalid_volume_slice_counts/: time point 1 has all 6 slices, time point 2 only slices 3..6;
- invalid_volume_missing_slice/: time point 2 lacks slice 3 (its other 5 slices are there);

and the fuzz_dicom seed two_time_points.dcm (two slices of each time point). The valid
fixtures of tests/data/dicom take the first 3 slices of time points 1 and 2 as two volumes told
apart by one other attribute each, with no TemporalPositionIdentifier. Classic MR files:

- two_echoes/: EchoNumbers 1 and 2 (EchoTime 10 and 30 ms), as a multi-echo series;
- two_bvalues/: DiffusionBValue 0 and 1000 (FD), as a diffusion series;
- two_image_types/: ImageType ORIGINAL\\PRIMARY\\M\\ND and ...\\P\\ND (magnitude and phase);
- two_complex_components/: ComplexImageComponent MAGNITUDE and PHASE;
- two_trigger_times/: TriggerTime 0 and 400 ms (two cardiac phases);
- two_acquisitions/: only AcquisitionTime (time point 2 acquired first).

One enhanced MR file each (the two volumes' frames interleaved, slice by slice):

- two_stacks.dcm: StackID 1 and 2 at the same positions;
- two_dimension_indices.dcm: DimensionIndexValues alone (dimensions InStackPositionNumber and
  InversionTimes), and its 4 x 4 pixel copy as the fuzz_dicom seed two_dimension_indices.dcm;
- two_gradient_directions.dcm: DiffusionGradientOrientation 0,1,0 and 1,0,0 at b-value 1000.

Run once from this folder with the shared data beside the checkout; the outputs are committed."""
import os
import struct

from make_fixtures import HERE, INVALID, MR_IMAGE, SEEDS, SEPARATOR, SHARED, ds, fresh, image, write

NIFTI = os.path.join(SHARED, "siemens_xa10_fmri_4d", "reference_dcm2niix.nii")
SERIES = "1.2.826.0.1.3680043.9.7777.90"
ENHANCED_MR = "1.2.840.10008.5.1.4.1.1.4.1"
STACK_ID, IN_STACK_POSITION, FRAME_CONTENT = (0x0020, 0x9056), (0x0020, 0x9057), (0x0020, 0x9111)


def read_nifti(path):
    """dims (nx, ny, nz, nt), the sform rows (RAS) and the int16 samples, x fastest."""
    with open(path, "rb") as f:
        data = f.read()
    dim = struct.unpack("<8h", data[40:56])
    datatype, = struct.unpack("<h", data[70:72])
    assert datatype == 4, "int16 expected"  # dcm2niix's output for this series
    offset = int(struct.unpack("<f", data[108:112])[0])
    srow = [struct.unpack("<4f", data[280 + 16 * r:296 + 16 * r]) for r in range(3)]
    nx, ny, nz, nt = dim[1:5]
    samples = struct.unpack("<%dh" % (nx * ny * nz * nt), data[offset:offset + 2 * nx * ny * nz * nt])
    return (nx, ny, nz, nt), srow, samples


def crop(dims, srow, samples, x0, y0, n):
    """The n x n pixels from (x0, y0) of every slice and time point, with the sform moved to them."""
    nx, ny, nz, nt = dims
    rows = [list(r) for r in srow]
    for r in range(3):
        rows[r][3] += x0 * srow[r][0] + y0 * srow[r][1]
    out = [samples[((s * ny) + y) * nx + x] for s in range(nz * nt) for y in range(y0, y0 + n) for x in range(x0, x0 + n)]
    return (n, n, nz, nt), rows, out


def lps(ras):
    return (-ras[0], -ras[1], ras[2])


def slice_geometry(dims, srow, samples, t, k):
    """Slice k of time point t: its origin, row and column directions (LPS), pixel spacing (between
    rows, between columns) and pixels (rows of nx samples)."""
    nx, ny, nz, _ = dims
    column = [[srow[r][a] for r in range(3)] for a in range(3)]  # RAS step along i, j, k
    length = [sum(c * c for c in column[a]) ** 0.5 for a in range(2)]
    row_dir = lps([c / length[0] for c in column[0]])
    col_dir = lps([c / length[1] for c in column[1]])
    origin = lps([srow[r][3] + k * column[2][r] for r in range(3)])
    start = ((t * nz + k) * ny) * nx
    return origin, row_dir, col_dir, (length[1], length[0]), list(samples[start:start + nx * ny])


def write_volume(folder, dims, srow, samples, t, slices, key=None, name="t%d_s%d.dcm"):
    """Slices `slices` of time point t; `key`: the elements that tell the volume apart
    (default: TemporalPositionIdentifier t + 1), or a function of the slice index giving them."""
    nx, ny = dims[:2]
    for k in slices:
        origin, row_dir, col_dir, spacing, pixels = slice_geometry(dims, srow, samples, t, k)
        extra = {
            (0x0020, 0x0032): ("DS", ds(*origin)),
            (0x0020, 0x0037): ("DS", ds(*row_dir, *col_dir)),
            (0x0028, 0x0030): ("DS", ds(*spacing)),
        }
        if key is None:
            key_k = {(0x0020, 0x0100): ("IS", str(t + 1))}  # TemporalPositionIdentifier
        else:
            key_k = key(k) if callable(key) else key
        extra.update(key_k)
        write(os.path.join(folder, name % (t + 1, k + 1)),
              image(SERIES, "MR", ny, nx, pixels, extra=extra, description="xa10 fmri slices"), MR_IMAGE)


def write_enhanced(path, dims, srow, samples, frames, dimensions, uid):
    """One enhanced MR file whose frames are (t, k, per-frame functional group items) in this
    order: slice k of time point t with its PlanePosition and the given macros; `dimensions`: the
    DimensionIndexPointers (tag, functional group tag) of its DimensionIndexSequence, if any."""
    nx, ny = dims[:2]
    per_frame, pixels = [], []
    for t, k, groups in frames:
        origin, row_dir, col_dir, spacing, values = slice_geometry(dims, srow, samples, t, k)
        item = {(0x0020, 0x9113): ("SQ", [{(0x0020, 0x0032): ("DS", ds(*origin))}])}  # Plane Position
        item.update(groups)
        per_frame.append(item)
        pixels += values
    shared = [{
        (0x0020, 0x9116): ("SQ", [{(0x0020, 0x0037): ("DS", ds(*row_dir, *col_dir))}]),  # Plane Orientation
        (0x0028, 0x9110): ("SQ", [{(0x0028, 0x0030): ("DS", ds(*spacing))}]),  # Pixel Measures
    }]
    index = [{(0x0020, 0x9165): ("AT", struct.pack("<HH", *tag)), (0x0020, 0x9167): ("AT", struct.pack("<HH", *group))}
             for tag, group in dimensions]
    extra = {(0x5200, 0x9229): ("SQ", shared), (0x5200, 0x9230): ("SQ", per_frame)}
    if index:
        extra[(0x0020, 0x9222)] = ("SQ", index)
    write(path, image(uid, "MR", ny, nx, pixels, frames=len(frames), extra=extra, description="xa10 fmri frames"),
          ENHANCED_MR)


def frame_content(**values):
    """A Frame Content Sequence (0020,9111) item: StackID, InStackPositionNumber, DimensionIndexValues."""
    tags = {"stack": (0x0020, 0x9056, "SH"), "in_stack": (0x0020, 0x9057, "UL"), "index": (0x0020, 0x9157, "UL")}
    item = {}
    for name, value in values.items():
        g, e, vr = tags[name]
        if isinstance(value, tuple):  # several UL values
            value = struct.pack("<%dI" % len(value), *value)
        item[(g, e)] = (vr, value)
    return {(0x0020, 0x9111): ("SQ", [item])}


def main():
    dims, srow, samples = read_nifti(NIFTI)
    nz = dims[2]
    d = fresh(os.path.join(INVALID, "invalid_volume_slice_counts"))
    write_volume(d, dims, srow, samples, 0, range(nz))
    write_volume(d, dims, srow, samples, 1, range(2, nz))
    d = fresh(os.path.join(INVALID, "invalid_volume_missing_slice"))
    write_volume(d, dims, srow, samples, 0, range(nz))
    write_volume(d, dims, srow, samples, 1, [k for k in range(nz) if k != 2])
    # A fuzz_dicom seed (up to 4 files joined by its separator): two time points of two slices each.
    with open(os.path.join(SEEDS, "two_time_points.dcm"), "wb") as f:
        f.write(SEPARATOR.join(open(os.path.join(d, name), "rb").read()
                               for name in ["t1_s1.dcm", "t1_s2.dcm", "t2_s1.dcm", "t2_s2.dcm"]))

    # Two echoes and two b-values (volumes of classic files without a temporal position).
    d = fresh(os.path.join(HERE, "two_echoes"))
    for t, (echo, te) in enumerate([(1, 10), (2, 30)]):
        write_volume(d, dims, srow, samples, t, range(3), {(0x0018, 0x0086): ("IS", str(echo)), (0x0018, 0x0081): ("DS", ds(te))},
                     "echo%d_s%d.dcm")
    d = fresh(os.path.join(HERE, "two_bvalues"))
    for t, b in enumerate([0, 1000]):
        write_volume(d, dims, srow, samples, t, range(3), {(0x0018, 0x9087): ("FD", struct.pack("<d", b))}, "b%d_s%d.dcm")

    # The other attributes that tell volumes apart, each alone (two volumes of 3 slices, time
    # points 1 and 2). Classic files: magnitude and phase told apart by ImageType (Siemens'
    # M and P), or by ComplexImageComponent; two cardiac phases (TriggerTime, ms).
    for folder, keys in [
            ("two_image_types", [{(0x0008, 0x0008): ("CS", "ORIGINAL\\PRIMARY\\M\\ND")},
                                 {(0x0008, 0x0008): ("CS", "ORIGINAL\\PRIMARY\\P\\ND")}]),
            ("two_complex_components", [{(0x0008, 0x9208): ("CS", "MAGNITUDE")}, {(0x0008, 0x9208): ("CS", "PHASE")}]),
            ("two_trigger_times", [{(0x0018, 0x1060): ("DS", ds(0))}, {(0x0018, 0x1060): ("DS", ds(400))}])]:
        d = fresh(os.path.join(HERE, folder))
        for t, key in enumerate(keys):
            write_volume(d, dims, srow, samples, t, range(3), key, "v%d_s%d.dcm")
    # Nothing but AcquisitionTime: time point 2 acquired first (12:00:00, a slice every 0.5 s),
    # time point 1 two seconds later; its files come first in name order.
    d = fresh(os.path.join(HERE, "two_acquisitions"))
    for t, start in [(0, 2.0), (1, 0.0)]:
        write_volume(d, dims, srow, samples, t, range(3),
                     lambda k, start=start: {(0x0008, 0x0032): ("TM", "1200%06.3f" % (start + 0.5 * k))}, "t%d_s%d.dcm")
    # Enhanced MR files (one each), the frames of the two volumes interleaved (slice 1 of time
    # points 1 and 2, then slice 2, ...): two stacks at the same positions (StackID 1 and 2,
    # dimensions StackID and InStackPositionNumber);
    interleaved = [(t, k) for k in range(3) for t in range(2)]
    write_enhanced(os.path.join(HERE, "two_stacks.dcm"), dims, srow, samples,
                   [(t, k, frame_content(stack=str(t + 1), in_stack=k + 1, index=(t + 1, k + 1))) for t, k in interleaved],
                   [(STACK_ID, FRAME_CONTENT), (IN_STACK_POSITION, FRAME_CONTENT)], SERIES + ".1")
    # two inversion times (an attribute octrace does not read) told apart only by
    # DimensionIndexValues, whose dimensions are InStackPositionNumber and InversionTimes (in the
    # MR Modifier macro);
    inversion_frames = [(t, k, {**frame_content(in_stack=k + 1, index=(k + 1, t + 1)),
                                (0x0018, 0x9115): ("SQ", [{(0x0018, 0x9079): ("FD", struct.pack("<d", [100, 1000][t]))}])})
                        for t, k in interleaved]
    inversion_dimensions = [(IN_STACK_POSITION, FRAME_CONTENT), ((0x0018, 0x9079), (0x0018, 0x9115))]
    write_enhanced(os.path.join(HERE, "two_dimension_indices.dcm"), dims, srow, samples, inversion_frames,
                   inversion_dimensions, SERIES + ".2")
    # two diffusion directions of one b-value (MR Diffusion macro: DiffusionBValue 1000 and the
    # DiffusionGradientOrientation in its Diffusion Gradient Direction Sequence).
    directions = [(0.0, 1.0, 0.0), (1.0, 0.0, 0.0)]
    write_enhanced(os.path.join(HERE, "two_gradient_directions.dcm"), dims, srow, samples,
                   [(t, k, {(0x0018, 0x9117): ("SQ", [{
                       (0x0018, 0x9087): ("FD", struct.pack("<d", 1000)),
                       (0x0018, 0x9075): ("CS", "DIRECTIONAL"),
                       (0x0018, 0x9076): ("SQ", [{(0x0018, 0x9089): ("FD", struct.pack("<3d", *directions[t]))}])}])})
                    for t, k in interleaved], [], SERIES + ".3")
    # A fuzz_dicom seed: the DimensionIndexValues case on 4 x 4 pixels of the phantom's middle.
    write_enhanced(os.path.join(SEEDS, "two_dimension_indices.dcm"), *crop(dims, srow, samples, 30, 30, 4),
                   inversion_frames, inversion_dimensions, SERIES + ".2")


if __name__ == "__main__":
    main()
