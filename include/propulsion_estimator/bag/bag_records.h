#pragma once

#include <string>

namespace propulsion_estimator {

/// @file
/// A guard before rosbag opens a file: rosbag allocates each record's buffer at the length the
/// file states, so a corrupt length would ask for gigabytes (found by fuzz_flight_bag).

/// What checkBagRecords() found.
struct BagRecordCheck {
  std::string damage;  ///< "" for a bag rosbag may read; else the problem (checkBagRecords())
  /// Whether the damage lies past the bag header record (the first): the records before it are
  /// whole, and `rosbag reindex` rebuilds an index from them.
  bool past_bag_header = false;
};

/// Walks the records of the rosbag v2.0 file at `path` (its version line, then records: header
/// length, header, data length, data) before rosbag reads it. Its damage is "" when every record's
/// header and data lie within the file; every chunk's stated uncompressed size is plausible (equal to its data
/// without compression, at most 1000 times its data and 1 GiB with it); every header's fields, and
/// a connection record's data's, fill it exactly (rosbag's parser reads past them otherwise); the
/// records inside an uncompressed chunk lie within it; and what rosbag follows without checking
/// points at a record (the bag header's index position, each chunk info's chunk, each index
/// entry's offset into its chunk). Else "at byte <offset>: <problem>" for the first record that is
/// not. A file whose first line is not, as rosbag reads it, a version line of 2.0 ("#ROS<name>
/// V2.0") gives "" (rosbag reads or refuses it). Reads the headers and the data of uncompressed
/// chunks, connection and index records.
BagRecordCheck checkBagRecords(const std::string& path);

}  // namespace propulsion_estimator
