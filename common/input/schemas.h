// The JSON Schemas of schemas/, compiled into the programs (generated from the files by
// common/cmake/EmbedFiles.cmake at build time).
#pragma once

namespace ffriga {

extern const char* const kBodySchema;   // schemas/body.schema.json
extern const char* const kSceneSchema;  // schemas/scene.schema.json

}  // namespace ffriga
