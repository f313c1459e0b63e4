#include "core/io/FileDigest.h"

#include <openssl/evp.h>

#include <memory>
#include <stdexcept>

#include "core/common/InputError.h"
#include "core/io/InputFile.h"

namespace activetouch {
namespace {

struct Hasher {
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx{EVP_MD_CTX_new(), &EVP_MD_CTX_free};
    Hasher() {
        if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
            throw std::runtime_error("SHA-256 is not available from libcrypto");
    }
    void add(const char* data, std::size_t n) { EVP_DigestUpdate(ctx.get(), data, n); }
    std::string hex() {
        unsigned char digest[EVP_MAX_MD_SIZE];
        unsigned int length = 0;
        EVP_DigestFinal_ex(ctx.get(), digest, &length);
        static const char* const kHex = "0123456789abcdef";
        std::string out;
        for (unsigned int i = 0; i < length; ++i) {
            out += kHex[digest[i] >> 4];
            out += kHex[digest[i] & 15];
        }
        return out;
    }
};

}  // namespace

std::string sha256OfFile(const std::string& path) {
    std::ifstream in = openInputFile(path, std::ios::binary);
    Hasher h;
    char chunk[BoundedLines::kChunkBytes];
    while (in) {
        in.read(chunk, sizeof chunk);
        h.add(chunk, static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) throw InputError(path, "", "reading the file failed; check the disk");
    return h.hex();
}

std::string sha256Of(const std::string& bytes) {
    Hasher h;
    h.add(bytes.data(), bytes.size());
    return h.hex();
}

}  // namespace activetouch
