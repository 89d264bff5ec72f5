#include "gl/spirv_op_counts.h"

#include <spirv_cross/GLSL.std.450.h>
#include <spirv_cross/spirv.h>

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace rl {
namespace {

struct Instruction {
  SpvOp op;
  std::vector<uint32_t> words;  // the whole instruction, its first word included
};

std::vector<Instruction> parse(const std::vector<uint32_t>& spirv) {
  if (spirv.size() < 5 || spirv[0] != SpvMagicNumber)
    throw std::runtime_error("op counting: not a SPIR-V module");
  std::vector<Instruction> out;
  for (size_t i = 5; i < spirv.size();) {
    const uint32_t count = spirv[i] >> 16;
    if (count == 0 || i + count > spirv.size())
      throw std::runtime_error("op counting: a SPIR-V instruction runs past the module's end");
    out.push_back({SpvOp(spirv[i] & 0xffff), {spirv.begin() + i, spirv.begin() + i + count}});
    i += count;
  }
  return out;
}

// What the module declares that classifying an instruction needs.
struct ModuleFacts {
  std::unordered_map<uint32_t, uint32_t> type_of;     // result id -> its type id
  std::unordered_map<uint32_t, uint32_t> components;  // type id -> scalar components
  std::set<uint32_t> float_types, constants;
  std::unordered_map<uint32_t, uint32_t> pointer_storage;  // pointer type id -> storage class
  std::map<std::string, uint32_t> names;                   // OpName, first of each
  std::set<uint32_t> uncounted;  // functions named rl_uncounted_*: the harness's, not the pass's
  // Increments of the harness's own fetch and iteration counters (search_cost.glsl): nothing in
  // the timed program reads them, so a GPU's compiler removes them.
  std::set<uint32_t> bookkeeping;
  uint32_t glsl_std = 0;  // GLSL.std.450's import id
};

std::string literal_string(const std::vector<uint32_t>& w, size_t from) {
  std::string s;
  for (size_t i = from; i < w.size(); ++i)
    for (int b = 0; b < 4; ++b) {
      const char c = char((w[i] >> (8 * b)) & 0xff);
      if (!c) return s;
      s += c;
    }
  return s;
}

void record_type(const Instruction& in, ModuleFacts& f) {
  const auto& w = in.words;
  switch (in.op) {
    case SpvOpTypeBool:
    case SpvOpTypeInt:
      f.components[w[1]] = 1;
      break;
    case SpvOpTypeFloat:
      f.components[w[1]] = 1;
      f.float_types.insert(w[1]);
      break;
    case SpvOpTypeVector:
    case SpvOpTypeMatrix:
      f.components[w[1]] = f.components[w[2]] * w[3];
      if (f.float_types.count(w[2])) f.float_types.insert(w[1]);
      break;
    case SpvOpTypePointer:
      f.pointer_storage[w[1]] = w[2];
      break;
    default:
      break;
  }
}

// The results of `rl_fetches++`, `rl_iterations += n` and the like: an integer add or subtract
// of a value loaded from one of those counters whose result is stored back into it.
std::set<uint32_t> bookkeeping_of(const std::vector<Instruction>& module, const ModuleFacts& f) {
  std::set<uint32_t> counters, loaded, stored;
  for (const char* name : {"rl_fetches", "rl_iterations"}) {
    const auto it = f.names.find(name);
    if (it != f.names.end()) counters.insert(it->second);
  }
  for (const Instruction& in : module) {
    if (in.op == SpvOpLoad && counters.count(in.words[3])) loaded.insert(in.words[2]);
    if (in.op == SpvOpStore && counters.count(in.words[1])) stored.insert(in.words[2]);
  }
  std::set<uint32_t> out;
  for (const Instruction& in : module)
    if ((in.op == SpvOpIAdd || in.op == SpvOpISub) && stored.count(in.words[2]) &&
        (loaded.count(in.words[3]) || loaded.count(in.words[4])))
      out.insert(in.words[2]);
  return out;
}

ModuleFacts facts_of(const std::vector<Instruction>& module) {
  ModuleFacts f;
  for (const Instruction& in : module) {
    bool has_result = false, has_type = false;
    SpvHasResultAndType(in.op, &has_result, &has_type);
    if (has_result && has_type) f.type_of[in.words[2]] = in.words[1];
    record_type(in, f);
    if (in.op == SpvOpName) {
      const std::string name = literal_string(in.words, 2);
      f.names.emplace(name, in.words[1]);
      if (name.rfind(kUncountedPrefix, 0) == 0) f.uncounted.insert(in.words[1]);
    }
    if (in.op == SpvOpExtInstImport && literal_string(in.words, 2) == "GLSL.std.450")
      f.glsl_std = in.words[1];
    if (in.op >= SpvOpConstantTrue && in.op <= SpvOpSpecConstantOp) f.constants.insert(in.words[2]);
  }
  f.bookkeeping = bookkeeping_of(module, f);
  return f;
}

uint32_t result_components(const Instruction& in, const ModuleFacts& f) {
  const auto it = f.components.find(in.words[1]);
  return it == f.components.end() ? 1 : it->second;
}

uint32_t operand_components(uint32_t id, const ModuleFacts& f) {
  const auto t = f.type_of.find(id);
  if (t == f.type_of.end()) return 1;
  const auto c = f.components.find(t->second);
  return c == f.components.end() ? 1 : c->second;
}

void count_glsl_std(const Instruction& in, const ModuleFacts& f, OpCounts& c) {
  const uint32_t n = result_components(in, f);
  const uint32_t operand_n = in.words.size() > 5 ? operand_components(in.words[5], f) : 1;
  const auto op = GLSLstd450(in.words[4]);
  switch (op) {
    case GLSLstd450Length:
    case GLSLstd450Distance:
      c[int(OpKind::Float)] += 2 * operand_n;
      c[int(OpKind::Special)] += 1;
      return;
    case GLSLstd450Normalize:
      c[int(OpKind::Float)] += 3 * operand_n;
      c[int(OpKind::Special)] += 1;
      return;
    default:
      break;
  }
  if (op >= GLSLstd450Sin && op <= GLSLstd450InverseSqrt)  // trigonometry, pow, exp, log, sqrt
    c[int(OpKind::Special)] += n;
  else if (op == GLSLstd450SAbs || op == GLSLstd450SSign || op == GLSLstd450UMin ||
           op == GLSLstd450SMin || op == GLSLstd450UMax || op == GLSLstd450SMax ||
           op == GLSLstd450UClamp || op == GLSLstd450SClamp ||
           (op >= GLSLstd450FindILsb && op <= GLSLstd450FindUMsb) ||
           (op >= GLSLstd450PackSnorm4x8 && op <= GLSLstd450UnpackDouble2x32))
    c[int(OpKind::Int)] += n;
  else
    c[int(OpKind::Float)] += n;
}

bool is_dynamic_local_access(const Instruction& in, const ModuleFacts& f) {
  const auto base_type = f.type_of.find(in.words[3]);
  if (base_type == f.type_of.end()) return false;
  const auto storage = f.pointer_storage.find(base_type->second);
  if (storage == f.pointer_storage.end() ||
      (storage->second != SpvStorageClassFunction && storage->second != SpvStorageClassPrivate))
    return false;
  for (size_t i = 4; i < in.words.size(); ++i)
    if (!f.constants.count(in.words[i])) return true;
  return false;
}

// Adds what `in` executes to `c`.
void count(const Instruction& in, const ModuleFacts& f, OpCounts& c) {
  const SpvOp op = in.op;
  if ((op == SpvOpIAdd || op == SpvOpISub) && f.bookkeeping.count(in.words[2])) return;
  if (op >= SpvOpImageSampleImplicitLod && op <= SpvOpImageRead) {
    c[int(OpKind::Fetch)] += 1;
  } else if (op == SpvOpFDiv || op == SpvOpFRem || op == SpvOpFMod) {
    c[int(OpKind::Special)] += result_components(in, f);
  } else if (op == SpvOpDot) {
    c[int(OpKind::Float)] += operand_components(in.words[3], f);
  } else if (op == SpvOpMatrixTimesVector || op == SpvOpVectorTimesMatrix ||
             op == SpvOpMatrixTimesMatrix || op == SpvOpOuterProduct) {
    c[int(OpKind::Float)] += result_components(in, f) * operand_components(in.words[4], f);
  } else if (op == SpvOpFNegate || op == SpvOpFAdd || op == SpvOpFSub || op == SpvOpFMul ||
             op == SpvOpVectorTimesScalar || op == SpvOpMatrixTimesScalar ||
             (op >= SpvOpConvertFToU && op <= SpvOpUConvert) || op == SpvOpFConvert ||
             op == SpvOpIsNan || op == SpvOpIsInf ||
             (op >= SpvOpFOrdEqual && op <= SpvOpFUnordGreaterThanEqual) ||
             (op >= SpvOpDPdx && op <= SpvOpFwidthCoarse)) {
    const uint32_t n = op >= SpvOpFOrdEqual && op <= SpvOpFUnordGreaterThanEqual
                           ? operand_components(in.words[3], f)
                           : result_components(in, f);
    c[int(OpKind::Float)] += n;
  } else if (op == SpvOpSelect) {
    c[int(f.float_types.count(in.words[1]) ? OpKind::Float : OpKind::Int)] +=
        result_components(in, f);
  } else if (op == SpvOpSNegate ||
             (op >= SpvOpIAdd && op <= SpvOpSMod && op != SpvOpFAdd && op != SpvOpFSub &&
              op != SpvOpFMul && op != SpvOpFDiv && op != SpvOpFRem && op != SpvOpFMod) ||
             (op >= SpvOpShiftRightLogical && op <= SpvOpBitCount) ||
             (op >= SpvOpLogicalEqual && op <= SpvOpSLessThanEqual) || op == SpvOpAny ||
             op == SpvOpAll || op == SpvOpVectorExtractDynamic || op == SpvOpVectorInsertDynamic) {
    c[int(OpKind::Int)] += result_components(in, f);
  } else if (op == SpvOpBranchConditional || op == SpvOpSwitch || op == SpvOpKill ||
             op == SpvOpTerminateInvocation) {
    c[int(OpKind::Branch)] += 1;
  } else if (op == SpvOpExtInst && in.words[3] == f.glsl_std) {
    count_glsl_std(in, f, c);
  } else if ((op == SpvOpAccessChain || op == SpvOpInBoundsAccessChain) &&
             is_dynamic_local_access(in, f)) {
    c[int(OpKind::DynamicIndex)] += 1;
  }
}

bool is_terminator(SpvOp op) {
  return op == SpvOpBranch || op == SpvOpBranchConditional || op == SpvOpSwitch ||
         op == SpvOpKill || op == SpvOpReturn || op == SpvOpReturnValue || op == SpvOpUnreachable ||
         op == SpvOpTerminateInvocation;
}

uint32_t word0(SpvOp op, size_t words) {
  return uint32_t(words << 16) | uint32_t(op);
}

// The instructions that add `by` to counter `var`: load, add, store.
void append_increment(std::vector<Instruction>& out, uint32_t uint_type, uint32_t var,
                      uint32_t constant, uint32_t& bound) {
  const uint32_t loaded = bound++, sum = bound++;
  out.push_back({SpvOpLoad, {word0(SpvOpLoad, 4), uint_type, loaded, var}});
  out.push_back({SpvOpIAdd, {word0(SpvOpIAdd, 5), uint_type, sum, loaded, constant}});
  out.push_back({SpvOpStore, {word0(SpvOpStore, 3), var, sum}});
}

}  // namespace

std::vector<OpCounts> block_op_counts(const std::vector<uint32_t>& spirv) {
  const std::vector<Instruction> module = parse(spirv);
  const ModuleFacts facts = facts_of(module);
  std::vector<OpCounts> blocks;
  bool counted = true;
  for (const Instruction& in : module) {
    if (in.op == SpvOpFunction) counted = !facts.uncounted.count(in.words[2]);
    if (in.op == SpvOpLabel) blocks.push_back({});
    if (!blocks.empty() && counted) count(in, facts, blocks.back());
  }
  return blocks;
}

std::vector<uint32_t> add_op_counters(const std::vector<uint32_t>& spirv) {
  const std::vector<Instruction> module = parse(spirv);
  const ModuleFacts facts = facts_of(module);
  // Each counter's variable, and the uint type they share.
  std::array<uint32_t, kOpKinds> counter{};
  uint32_t uint_type = 0;
  for (int k = 0; k < kOpKinds; ++k) {
    const auto it = facts.names.find(kOpCounterNames[k]);
    if (it == facts.names.end()) continue;
    counter[k] = it->second;
    const auto pointer = facts.type_of.find(counter[k]);
    for (const Instruction& in : module)
      if (pointer != facts.type_of.end() && in.op == SpvOpTypePointer &&
          in.words[1] == pointer->second)
        uint_type = in.words[3];
  }
  if (!uint_type) throw std::runtime_error("op counting: the shader declares no rl_ops_* counter");

  uint32_t bound = spirv[3];
  std::map<uint64_t, uint32_t> constant_of;  // value -> the OpConstant added for it
  auto constant = [&](uint64_t value) {
    auto [it, added] = constant_of.emplace(value, 0);
    if (added) it->second = bound++;
    return it->second;
  };
  const uint32_t zero = constant(0);
  // Each block adds its counts where it begins (after its phis and, in a function's first block,
  // its variables): a block runs whole once entered, and a call it makes -- the one that writes
  // the counts out, say -- then sees them.
  std::vector<Instruction> out;
  OpCounts block{};
  size_t block_start = 0;
  auto flush_block = [&] {
    std::vector<Instruction> adds;
    for (int k = 0; k < kOpKinds; ++k)
      if (counter[k] && block[k])
        append_increment(adds, uint_type, counter[k], constant(block[k]), bound);
    out.insert(out.begin() + long(block_start), adds.begin(), adds.end());
    block = {};
  };
  bool in_block = false, counted = true;
  for (const Instruction& in : module) {
    if (in.op == SpvOpFunction) counted = !facts.uncounted.count(in.words[2]);
    Instruction copy = in;
    // The counters start at zero: glslang would zero them in main's first block, which counts
    // itself before anything runs.
    if (in.op == SpvOpVariable && in.words.size() == 4 &&
        std::find(counter.begin(), counter.end(), in.words[2]) != counter.end()) {
      copy.words.push_back(zero);
      copy.words[0] = word0(SpvOpVariable, 5);
    }
    const bool block_head =
        in.op == SpvOpPhi || in.op == SpvOpVariable || in.op == SpvOpLine || in.op == SpvOpNoLine;
    if (in_block && out.size() == block_start && block_head) ++block_start;
    if (in_block && counted) count(in, facts, block);
    out.push_back(copy);
    if (in.op == SpvOpLabel) {
      in_block = true;
      block = {};
      block_start = out.size();
    }
    if (is_terminator(in.op)) {
      flush_block();
      in_block = false;
    }
  }
  // The constants, right after the counters' type (which precedes every use of them).
  std::vector<uint32_t> words(spirv.begin(), spirv.begin() + 5);
  for (const Instruction& in : out) {
    words.insert(words.end(), in.words.begin(), in.words.end());
    if (in.op == SpvOpTypeInt && in.words[1] == uint_type)
      for (const auto& [value, id] : constant_of) {
        const uint32_t c[] = {word0(SpvOpConstant, 4), uint_type, id, uint32_t(value)};
        words.insert(words.end(), std::begin(c), std::end(c));
      }
  }
  words[3] = bound;
  return words;
}

std::vector<uint32_t> without_assigned_locations(const std::vector<uint32_t>& spirv) {
  const std::vector<Instruction> module = parse(spirv);
  std::unordered_map<uint32_t, uint32_t> storage_of;  // variable -> storage class
  std::unordered_map<uint32_t, uint32_t> pointee;     // pointer type -> pointee type
  std::unordered_map<uint32_t, uint32_t> element;     // array type -> element type
  std::set<uint32_t> opaque;                          // image, sampler, sampled image types
  for (const Instruction& in : module) {
    const auto& w = in.words;
    if (in.op == SpvOpTypePointer) pointee[w[1]] = w[3];
    if (in.op == SpvOpTypeArray || in.op == SpvOpTypeRuntimeArray) element[w[1]] = w[2];
    if (in.op == SpvOpTypeImage || in.op == SpvOpTypeSampler || in.op == SpvOpTypeSampledImage)
      opaque.insert(w[1]);
    if (in.op == SpvOpVariable) storage_of[w[2]] = w[3];
  }
  std::unordered_map<uint32_t, uint32_t> type_of_variable;
  for (const Instruction& in : module)
    if (in.op == SpvOpVariable) type_of_variable[in.words[2]] = in.words[1];
  auto is_opaque = [&](uint32_t variable) {
    uint32_t t = pointee[type_of_variable[variable]];
    while (element.count(t)) t = element[t];
    return opaque.count(t) > 0;
  };
  std::vector<uint32_t> out(spirv.begin(), spirv.begin() + 5);
  for (const Instruction& in : module) {
    bool drop = false;
    if (in.op == SpvOpDecorate && storage_of.count(in.words[1])) {
      const uint32_t storage = storage_of[in.words[1]];
      const uint32_t decoration = in.words[2];
      const bool plain_uniform = storage == SpvStorageClassUniformConstant;
      drop = (decoration == SpvDecorationLocation &&
              (storage == SpvStorageClassInput || plain_uniform)) ||
             (decoration == SpvDecorationBinding && plain_uniform && !is_opaque(in.words[1]));
    }
    if (!drop) out.insert(out.end(), in.words.begin(), in.words.end());
  }
  return out;
}

}  // namespace rl
