"""mavros_msgs/RCOut for tests, without mavros_msgs (Debian does not package it).

Encodes the wire format by hand: the estimator under test decodes it independently in C++."""
import struct

import genpy
from std_msgs.msg import Header

_HEADER_DEFINITION = Header._full_text


class RCOut(genpy.Message):
    _md5sum = "52cacf104bab5ae3b103cfe176590713"
    _type = "mavros_msgs/RCOut"
    _has_header = True
    _full_text = ("# RAW Servo out state\n\nstd_msgs/Header header\nuint16[] channels\n\n" + "=" * 80 +
                  "\nMSG: std_msgs/Header\n" + _HEADER_DEFINITION)
    __slots__ = ["header", "channels"]
    _slot_types = ["std_msgs/Header", "uint16[]"]

    def __init__(self, *args, **kwds):
        super().__init__(*args, **kwds)
        if self.header is None:
            self.header = Header()
        if self.channels is None:
            self.channels = []

    def serialize(self, buff):
        frame = self.header.frame_id.encode()
        buff.write(struct.pack("<3I", self.header.seq, self.header.stamp.secs, self.header.stamp.nsecs))
        buff.write(struct.pack("<I", len(frame)) + frame)
        buff.write(struct.pack("<I%dH" % len(self.channels), len(self.channels), *self.channels))

    def deserialize(self, data):
        seq, secs, nsecs, frame_len = struct.unpack_from("<4I", data, 0)
        offset = 16 + frame_len
        self.header = Header(seq=seq, stamp=genpy.Time(secs, nsecs), frame_id=data[16:offset].decode())
        (count,) = struct.unpack_from("<I", data, offset)
        self.channels = list(struct.unpack_from("<%dH" % count, data, offset + 4))
        return self
