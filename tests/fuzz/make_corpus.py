#!/usr/bin/env python3
"""Writes the seed corpora of the LAS, LAZ and text reader fuzzers (tests/fuzz/corpus/{las,laz,text}).

Small synthetic files, one per layout the readers know: every LAS version and point format,
GeoTIFF-key and WKT CRS records, an EVLR, extra bytes, a LAZ-marked and a truncated header; LAZ
with each compressor and item set (a raw first point, then bytes for the decoders to take
apart; chunked ones without a finished table, so the reader rebuilds it by decoding); text
with every delimiter, header lines, comments, CRLF, quotes. Run from anywhere; overwrites the
seeds. gdalsrsinfo (gdal-bin) supplies the WKT of the CRS records.
"""
import os
import struct
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
MIN_LENGTH = [20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67]


def wkt_of(code):
    return subprocess.run(["gdalsrsinfo", "-o", "wkt1", code], check=True,
                          capture_output=True, text=True).stdout.strip()


def vlr(user, record, data, extended=False):
    user = user.encode().ljust(16, b"\0")
    desc = b"seed".ljust(32, b"\0")
    if extended:
        return struct.pack("<H16sHQ32s", 0, user, record, len(data), desc) + data
    return struct.pack("<H16sHH32s", 0, user, record, len(data), desc) + data


def las(minor, fmt, points, vlrs=b"", nvlr=0, evlrs=b"", nevlr=0, extra=0, wkt_bit=False,
        format_byte=None):
    header_size = 375 if minor >= 4 else 235 if minor == 3 else 227
    reclen = MIN_LENGTH[fmt] + extra
    offset = header_size + len(vlrs)
    h = bytearray(header_size)
    h[0:4] = b"LASF"
    struct.pack_into("<H", h, 6, 0x10 if wkt_bit else 0)
    h[24], h[25] = 1, minor
    h[26:58] = b"fuzz seed".ljust(32, b"\0")
    struct.pack_into("<HIIBHI", h, 94, header_size, offset, nvlr,
                     fmt if format_byte is None else format_byte, reclen, len(points))
    struct.pack_into("<3d3d", h, 131, 0.01, 0.01, 0.01, 500000.0, 4900000.0, 0.0)
    body = bytearray()
    for i, (x, y, z, rn, nr, cls) in enumerate(points):
        rec = bytearray(reclen)
        struct.pack_into("<iiiH", rec, 0, x, y, z, 100 + i)
        if fmt >= 6:
            rec[14] = (rn & 15) | ((nr & 15) << 4)
            rec[16] = cls
        else:
            rec[14] = (rn & 7) | ((nr & 7) << 3)
            rec[15] = cls & 31
        body += rec
    data = bytes(h) + vlrs + bytes(body)
    if minor >= 4:
        data = bytearray(data)
        struct.pack_into("<Q", data, 247, len(points))
        if nevlr:
            struct.pack_into("<QI", data, 235, len(data), nevlr)
        data = bytes(data) + evlrs
    return data


def laszip_record(compressor, items, chunk_size=50000):
    """The payload of the 'laszip encoded' VLR: items as (type, size, version)."""
    head = struct.pack("<HHBBHIIqqH", compressor, 0, 3, 4, 3, 0, chunk_size, -1, -1, len(items))
    return head + b"".join(struct.pack("<HHH", *item) for item in items)


def laz(minor, fmt, count, compressor, items, extra=0):
    """A LAZ file of `count` points: its first point raw, then pseudo-random coded bytes. The
    chunked compressors' table pointer points at itself, as a writer interrupted before the
    table leaves it."""
    record = laszip_record(compressor, items)
    base = las(minor, fmt, POINTS[:1], vlr("laszip encoded", 22204, record), 1, extra=extra,
               format_byte=fmt | (0xC0 if fmt >= 6 else 0x80))
    data = bytearray(base)
    struct.pack_into("<I", data, 107, count if fmt < 6 else 0)
    if minor >= 4:
        struct.pack_into("<Q", data, 247, count)
    offset = struct.unpack_from("<I", data, 96)[0]
    first_point = bytes(data[offset:])
    del data[offset:]
    if compressor >= 2:
        data += struct.pack("<q", offset)
    noise = bytes((i * 197 + 89) % 256 for i in range(96))
    return bytes(data) + first_point + noise


POINTS = [(0, 0, 1000, 1, 1, 2), (1000, 0, 1100, 1, 2, 1), (0, 1000, 1200, 2, 2, 2),
          (1000, 1000, 900, 1, 1, 5), (500, 500, 1500, 3, 3, 2), (-250, 750, 800, 1, 1, 7)]


def geokeys(*keys):
    return struct.pack("<%dH" % (4 + 4 * len(keys)), 1, 1, 0, len(keys),
                       *[v for key in keys for v in key])


def write(kind, name, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(HERE, "corpus", kind, name), mode) as f:
        f.write(data)


def main():
    os.makedirs(os.path.join(HERE, "corpus", "las"), exist_ok=True)
    os.makedirs(os.path.join(HERE, "corpus", "laz"), exist_ok=True)
    os.makedirs(os.path.join(HERE, "corpus", "text"), exist_ok=True)
    wkt = wkt_of("EPSG:32619").encode() + b"\0"
    projected = vlr("LASF_Projection", 34735, geokeys((1024, 0, 1, 1), (1025, 0, 1, 1),
                                                      (3072, 0, 1, 32619)))
    geographic = (vlr("LASF_Projection", 34735,
                      geokeys((1024, 0, 1, 2), (1026, 34737, 8, 0), (2048, 0, 1, 4326),
                              (3077, 34736, 1, 0)))
                  + vlr("LASF_Projection", 34736, struct.pack("<d", 1.0))
                  + vlr("LASF_Projection", 34737, b"WGS 84|\0"))
    write("las", "v10_f0.las", las(0, 0, POINTS))
    write("las", "v11_f1.las", las(1, 1, POINTS))
    write("las", "v12_f2.las", las(2, 2, POINTS))
    write("las", "v12_f3_geokeys.las", las(2, 3, POINTS, projected, 1))
    write("las", "v12_f1_geokeys_params.las", las(2, 1, POINTS, geographic, 3))
    write("las", "v13_f4.las", las(3, 4, POINTS))
    write("las", "v13_f5.las", las(3, 5, POINTS[:2]))
    write("las", "v14_f6_wkt.las", las(4, 6, POINTS, vlr("LASF_Projection", 2112, wkt), 1,
                                       wkt_bit=True))
    write("las", "v14_f7_evlr.las", las(4, 7, POINTS, evlrs=vlr("LASF_Projection", 2112, wkt,
                                                                extended=True), nevlr=1,
                                        wkt_bit=True))
    write("las", "v14_f8.las", las(4, 8, POINTS))
    write("las", "v14_f9.las", las(4, 9, POINTS[:3]))
    write("las", "v14_f10_extra.las", las(4, 10, POINTS[:3], extra=5))
    write("las", "v12_f1_extra.las", las(2, 1, POINTS, extra=3))
    write("las", "laz_bit.las", las(2, 3, POINTS[:1], format_byte=3 | 0x80))
    write("las", "truncated.las", las(2, 1, POINTS)[:300])
    lying = bytearray(las(2, 1, POINTS))
    struct.pack_into("<I", lying, 107, 1000)
    write("las", "lying_count.las", bytes(lying))
    write("las", "empty_points.las", las(2, 0, []))
    # Format 99 (bit 6 without LASzip's bit 7) is an unknown format, not LAZ.
    write("las", "point_format_99.las", las(2, 3, POINTS[:1], format_byte=99))

    point10, gps, rgb, wave = (6, 20, 2), (7, 8, 2), (8, 6, 2), (9, 29, 1)
    write("laz", "c1_f1_v1.laz", laz(2, 1, 4, 1, [(6, 20, 1), (7, 8, 1)]))
    write("laz", "c1_f2_v2.laz", laz(2, 2, 4, 1, [point10, rgb]))
    write("laz", "c2_f3_v2.laz", laz(2, 3, 4, 2, [point10, gps, rgb]))
    write("laz", "c2_f1_byte.laz", laz(2, 1, 4, 2, [point10, gps, (0, 3, 2)], extra=3))
    write("laz", "c2_f4_wave.laz", laz(3, 4, 4, 2, [point10, gps, wave]))
    write("laz", "c3_f6.laz", laz(4, 6, 4, 3, [(10, 30, 3)]))
    write("laz", "c3_f7_byte.laz", laz(4, 7, 4, 3, [(10, 30, 3), (11, 6, 3), (14, 2, 3)],
                                       extra=2))
    write("laz", "c3_f8.laz", laz(4, 8, 4, 3, [(10, 30, 3), (12, 8, 3)]))
    write("laz", "c3_f10_wave.laz", laz(4, 10, 4, 3, [(10, 30, 3), (12, 8, 3), (13, 29, 3)]))

    write("text", "space.xyz", "500000.5 4900000.25 101.5\n500010 4900000 99\n500005 4900010 120.75\n")
    write("text", "comma_header.csv", "x,y,z,id\n1.5,2.5,3.5,1\n4,5,6,2\n7e2,8e-1,-9,3\n")
    write("text", "semicolon_crlf.txt", "E;N;H\r\n1;2;3\r\n4;5;6\r\n")
    write("text", "pipe.txt", "612345.125|218765.5|101.25|1|1\n"
                              "612340.0|218760.25|100.5|3|2\n"
                              "612350.75|218770.0|99.875|2|1\n")
    write("text", "tab.tsv", "lon\tlat\televation\n-71.5\t44.5\t100\n-71.4\t44.6\t200\n")
    write("text", "comments.xyz", "# exported by a survey\n\n  # indented comment\n1 2 3\n\n4 5 6\n")
    write("text", "quoted.csv", '"easting","northing","height"\n"1","2","3"\n"4","5","6"\n')
    write("text", "bad_number.xyz", "1 2 3\n4 5 six\n")
    write("text", "short_line.xyz", "1 2 3\n4 5\n")
    write("text", "signs.xyz", "+1 -2 +3.5e+2\n-0 .5 5.\n")
    write("text", "no_newline.xyz", "1 2 3\n4 5 6")
    # A UTF-8 byte order mark is skipped, not read as part of the first number.
    write("text", "utf8_bom.csv", "\ufeffx,y,z\r\n1,2,3\r\n4,5,6\r\n")
    write("text", "utf8_bom.xyz", "\ufeff1 2 3\n4 5 6\n")


if __name__ == "__main__":
    main()
