// The protobuf schema of an LCM type, made from its .lcm definition at run
// time: what mrsim-log --mcap puts in a protobuf channel's Schema record
// (encoding "protobuf", a serialised google.protobuf.FileDescriptorSet, as
// MCAP's well-known encodings and Foxglove ask), matching what
// LcmProtobufEncoder writes. Each LCM struct is a proto3 message of the
// same package and name ("mrsim.robot_state_t"), its members fields
// numbered in declaration order from 1: int8_t/int16_t/int32_t sint32,
// int64_t int64, byte uint32, boolean bool, float, double, string; arrays
// repeated (numbers packed), byte arrays bytes; an array of more than one
// dimension a repeated wrapper message per row (NAME_row1 for the rows of
// member NAME, NAME_row2 for theirs, ...; field 1 "values" holds the row),
// nested structs their messages. One file per LCM package, "PACKAGE.proto".
#pragma once

#include <string>

#include "logger/lcm_type_registry.h"

namespace mrsim {

// The serialised FileDescriptorSet with `type` and every struct it uses,
// files in dependency order. Throws std::runtime_error when a member's
// type is not in the registry, or packages use each other in a circle.
std::string LcmProtobufDescriptorSet(const LcmTypeRegistry& registry,
                                     const LcmStruct& type);

// The suffix of a row wrapper's name before its level ("_row"): readers
// turn such messages back into nested arrays.
inline constexpr const char* kProtobufRowSuffix = "_row";

}  // namespace mrsim
