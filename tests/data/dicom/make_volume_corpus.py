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
apart by other attributes, with no TemporalPositionIdentifier:

- two_echoes/: EchoNumbers 1 and 2 (EchoTime 10 and 30 ms), as a multi-echo series;
- two_bvalues/: DiffusionBValue 0 and 1000 (FD), as a diffusion series.

Run once from this folder with the shared data beside the checkout; the outputs are committed."""
import os
import struct

from make_fixtures import HERE, INVALID, MR_IMAGE, SEEDS, SEPARATOR, SHARED, ds, fresh, image, write

NIFTI = os.path.join(SHARED, "siemens_xa10_fmri_4d", "reference_dcm2niix.nii")
SERIES = "1.2.826.0.1.3680043.9.7777.90"


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


def lps(ras):
    return (-ras[0], -ras[1], ras[2])


def write_volume(folder, dims, srow, samples, t, slices, key=None, name="t%d_s%d.dcm"):
    """Slices `slices` of time point t; `key`: the elements that tell the volume apart
    (default: TemporalPositionIdentifier t + 1)."""
    nx, ny, nz, _ = dims
    column = [[srow[r][a] for r in range(3)] for a in range(3)]  # RAS step along i, j, k
    length = [sum(c * c for c in column[a]) ** 0.5 for a in range(2)]
    row_dir = lps([c / length[0] for c in column[0]])
    col_dir = lps([c / length[1] for c in column[1]])
    for k in slices:
        origin = lps([srow[r][3] + k * column[2][r] for r in range(3)])
        start = ((t * nz + k) * ny) * nx
        pixels = list(samples[start:start + nx * ny])
        extra = {
            (0x0020, 0x0032): ("DS", ds(*origin)),
            (0x0020, 0x0037): ("DS", ds(*row_dir, *col_dir)),
            (0x0028, 0x0030): ("DS", ds(length[1], length[0])),  # between rows, between columns
        }
        extra.update(key if key is not None else {(0x0020, 0x0100): ("IS", str(t + 1))})  # TemporalPositionIdentifier
        write(os.path.join(folder, name % (t + 1, k + 1)),
              image(SERIES, "MR", ny, nx, pixels, extra=extra, description="xa10 fmri slices"), MR_IMAGE)


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


if __name__ == "__main__":
    main()
