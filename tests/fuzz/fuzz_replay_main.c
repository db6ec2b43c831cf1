/* The main() of a fuzz target when it is not linked with libFuzzer (the ordinary GCC build):
 * runs LLVMFuzzerTestOneInput once on every file given, and on every file of every folder given
 * and of its sub-folders (in name order; libFuzzer too reads a corpus recursively), so that seeds
 * and the inputs of fixed crashes are regression tests in CTest. A broken promise aborts inside
 * the target; a missing or empty corpus fails here, so a test never passes by replaying nothing. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

/* Runs the target on one file; returns 0, or -1 when it cannot be read. */
static int replay_file(const char* path) {
    FILE* file = fopen(path, "rb");
    if (!file) return -1;
    size_t capacity = 4096, size = 0;
    uint8_t* data = malloc(capacity);
    for (;;) {
        if (!data) {
            fclose(file);
            return -1;
        }
        size += fread(data + size, 1, capacity - size, file);
        if (size < capacity) break;
        capacity *= 2;
        data = realloc(data, capacity);
    }
    const int failed = ferror(file);
    fclose(file);
    if (failed) {
        free(data);
        return -1;
    }
    /* An exact-size copy, so that a read past the end is caught by the sanitizers as it is
     * under libFuzzer. */
    uint8_t* exact = malloc(size ? size : 1);
    if (!exact) {
        free(data);
        return -1;
    }
    memcpy(exact, data, size);
    free(data);
    LLVMFuzzerTestOneInput(exact, size);
    free(exact);
    return 0;
}

static int compare_names(const void* a, const void* b) {
    return strcmp(*(char* const*)a, *(char* const*)b);
}

/* Replays every regular file of `folder` and its sub-folders in name order; returns how many, or
 * -1. */
static long replay_folder(const char* folder) {
    DIR* dir = opendir(folder);
    if (!dir) return -1;
    char** names = NULL;
    size_t count = 0, capacity = 0;
    for (struct dirent* entry = readdir(dir); entry; entry = readdir(dir)) {
        if (entry->d_name[0] == '.') continue;
        if (count == capacity) {
            capacity = capacity ? 2 * capacity : 64;
            char** grown = realloc(names, capacity * sizeof(char*));
            if (!grown) break;
            names = grown;
        }
        names[count] = strdup(entry->d_name);
        if (names[count]) ++count;
    }
    closedir(dir);
    qsort(names, count, sizeof(char*), compare_names);
    long replayed = 0;
    for (size_t i = 0; i < count; ++i) {
        const size_t length = strlen(folder) + strlen(names[i]) + 2;
        char* path = malloc(length);
        if (path) {
            snprintf(path, length, "%s/%s", folder, names[i]);
            struct stat info;
            if (stat(path, &info) == 0 && S_ISDIR(info.st_mode)) {
                const long inside = replay_folder(path);  /* libFuzzer reads folders recursively */
                if (inside < 0) {
                    replayed = -1;
                } else if (replayed >= 0) {
                    replayed += inside;
                }
            } else if (stat(path, &info) == 0 && S_ISREG(info.st_mode)) {
                if (replay_file(path) != 0) {
                    fprintf(stderr, "cannot read %s\n", path);
                    replayed = -1;
                } else if (replayed >= 0) {
                    ++replayed;
                }
            }
            free(path);
        }
        free(names[i]);
    }
    free(names);
    return replayed;
}

int main(int argc, char** argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: %s FILE_OR_FOLDER...\n", argv[0]);
        return 2;
    }
    long total = 0;
    for (int a = 1; a < argc; ++a) {
        struct stat info;
        long replayed = -1;
        if (stat(argv[a], &info) == 0 && S_ISDIR(info.st_mode)) {
            replayed = replay_folder(argv[a]);
        } else if (replay_file(argv[a]) == 0) {
            replayed = 1;
        }
        if (replayed <= 0) {
            fprintf(stderr, "%s: %s holds no readable input\n", argv[0], argv[a]);
            return 1;
        }
        printf("%s: %ld inputs\n", argv[a], replayed);
        total += replayed;
    }
    printf("replayed %ld inputs, every promise kept\n", total);
    return 0;
}
