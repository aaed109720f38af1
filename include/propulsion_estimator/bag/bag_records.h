#pragma once

#include <string>

namespace propulsion_estimator {

/// @file
/// A guard before rosbag opens a file: rosbag allocates each record's buffer at the length the
/// file states, so a corrupt length would ask for gigabytes (found by fuzz_flight_bag).

/// Walks the records of the rosbag v2.0 file at `path` ("#ROSBAG V2.0" and its records: header
/// length, header, data length, data) before rosbag reads it: "" when every record's header and
/// data lie within the file, every chunk's stated uncompressed size is plausible (equal to its data
/// without compression, at most 1000 times its data and 1 GiB with it), every header's fields fill it
/// exactly, and so do a connection record's data's (rosbag's parser reads past them otherwise), the records inside an
/// uncompressed chunk lie within it, and what rosbag follows without checking points at a record
/// (the bag header's index position, each chunk info's chunk, each index entry's offset into its
/// chunk); else "at byte <offset>: <problem>" for the first record that is not. A file that does not
/// start with "#ROSBAG V2.0" gives "" (rosbag refuses it). Reads the headers, and the data of
/// uncompressed chunks and of index records.
std::string checkBagRecords(const std::string& path);

}  // namespace propulsion_estimator
