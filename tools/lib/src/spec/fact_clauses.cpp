// The facts in other words: a sentence's tokens into clauses of the table's phrases and its
// quantities, and the first look at a sentence (does it state anything, what might it have meant).
#include "fact_reader.hpp"

#include <regex>

namespace helios::spec::detail {
namespace {

// A bound word ("at most", "up to", "at least") with only fillers between it and the quantity
// after it bounds that quantity.
void mark_bound(std::vector<Mention>& mentions, std::size_t from, Quantity& q) {
  for (std::size_t k = mentions.size(); k > from; --k) {
    Mention& m = mentions[k - 1];
    if (filler(m.meaning)) continue;
    if (m.meaning.bound || m.meaning.lower) {
      m.on_quantity = true;
      q.at_most = m.meaning.bound;
      q.at_least = m.meaning.lower;
      q.bound_words = m.text;
    }
    return;
  }
}

}  // namespace

facts_error negation_error(const std::string& word) {
  return facts_error("'" + word +
                     "' negates what follows it: HELIOS reads facts stated as they are, never their negation");
}

// A word that states nothing ("the", "of", "to").
bool filler(const Meaning& m) {
  return m.slot == Slot::None && m.role == kNoRole && m.verb == kNoVerb && m.noun == kNoNoun && !m.bound &&
         m.body.empty() && !m.central && m.event.empty() && !m.lower && !m.named && m.model.empty() && !m.negation;
}

// Words into the longest phrases of the table; an unknown word is an error.
std::vector<Clause> clauses_of(const std::vector<Token>& tokens, const std::map<std::string, std::string>& names) {
  std::vector<Clause> out(1);
  std::vector<std::string> words;
  bool after_bare_number = false;  // the words follow a number without a unit
  std::size_t flushed_from = 0;    // the first mention of the words flushed last
  const auto flush = [&] {
    const auto& table = phrases();
    flushed_from = out.back().mentions.size();
    for (std::size_t i = 0; i < words.size();) {
      std::size_t len = std::min(kMaxPhraseWords, words.size() - i);
      for (; len > 0; --len) {
        std::string phrase = words[i];
        for (std::size_t k = 1; k < len; ++k) phrase += " " + words[i + k];
        const auto it = table.find(phrase);
        if (it != table.end()) {
          out.back().mentions.push_back({it->second, phrase});
          break;
        }
      }
      if (len == 0 && names.count(words[i])) {  // a body the text gives by name
        Meaning m;
        m.body = names.at(words[i]);
        m.named = true;
        out.back().mentions.push_back({m, words[i]});
        ++i;
        continue;
      }
      if (len == 0) {
        if (i == 0 && after_bare_number)
          throw facts_error("'" + words[i] + "' after " + out.back().quantities.back().written +
                            " is no unit HELIOS knows and no fact word");
        // a word before a fact word modifies it ("dry mass"): no form can be suggested
        bool modifies = false;
        for (std::size_t len2 = 1; i + len2 < words.size() && len2 <= kMaxPhraseWords && !modifies; ++len2) {
          std::string next = words[i + 1];
          for (std::size_t k = 1; k < len2; ++k) next += " " + words[i + 1 + k];
          const auto it = table.find(next);
          modifies = it != table.end() && it->second.slot != Slot::None;
        }
        facts_error e("cannot place the word '" + words[i] + "'");
        e.modifies_fact = modifies;
        throw e;
      }
      i += len;
    }
    words.clear();
  };
  for (const auto& t : tokens) {
    if (t.kind == Token::Word) {
      words.push_back(t.word);
      continue;
    }
    flush();
    after_bare_number = t.kind == Token::Value && t.q.unit.empty();
    if (t.kind == Token::Value) {
      out.back().quantities.push_back(t.q);
      mark_bound(out.back().mentions, flushed_from, out.back().quantities.back());
    }
    if (t.kind == Token::Separator && (!out.back().mentions.empty() || !out.back().quantities.empty()))
      out.emplace_back();
  }
  flush();
  if (out.back().mentions.empty() && out.back().quantities.empty()) out.pop_back();
  return out;
}

bool states_nothing(const std::string& sentence, const std::map<std::string, std::string>& names) {
  static const std::regex digit("[0-9]");
  if (std::regex_search(sentence, digit)) return false;
  std::vector<Token> tokens;
  try {
    tokens = scan(sentence);
  } catch (const facts_error&) {
    return true;
  }
  const auto& table = phrases();
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    if (tokens[i].kind != Token::Word) continue;
    if (names.count(tokens[i].word)) return false;
    std::string phrase;
    for (std::size_t k = i; k < tokens.size() && k < i + kMaxPhraseWords && tokens[k].kind == Token::Word; ++k) {
      phrase += (k == i ? "" : " ") + tokens[k].word;
      const auto it = table.find(phrase);
      const Meaning& mean = it == table.end() ? Meaning{} : it->second;
      if ((mean.slot != Slot::None && !mean.weak) || mean.verb != kNoVerb || !mean.body.empty() || mean.central ||
          !mean.event.empty() || !mean.model.empty() || mean.negation)
        return false;
    }
  }
  return true;
}

// For a sentence with a word that fits nowhere: the controlled form of its one scalar fact, if the
// sentence names exactly one and holds exactly one number.
std::string rough_suggestion(const std::vector<Token>& tokens) {
  std::set<Field> fields;
  std::vector<Candidate> cands;
  const Quantity* number = nullptr;
  int numbers = 0;
  bool bounded = false;  // a bound or a minimization: a time of flight so said is free, not fixed
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    if (tokens[i].kind == Token::Value) {
      ++numbers;
      const Quantity& q = tokens[i].q;
      if (!q.vector && !q.date && !q.day && !q.window) number = &q;  // a plain number only
    }
    if (tokens[i].kind != Token::Word) continue;
    std::string phrase;
    for (std::size_t len = 1; len <= kMaxPhraseWords && i + len <= tokens.size(); ++len) {
      if (tokens[i + len - 1].kind != Token::Word) break;
      phrase += (len == 1 ? "" : " ") + tokens[i + len - 1].word;
      const auto it = phrases().find(phrase);
      if (it == phrases().end()) continue;
      bounded = bounded || it->second.bound || it->second.verb == kMinimize;
      const Slot sl = it->second.slot;
      const bool named_fact = sl == Slot::Thrust || sl == Slot::Isp || sl == Slot::Mass || sl == Slot::InitialMass ||
                              sl == Slot::FinalMass || sl == Slot::Tof || sl == Slot::Mu;
      if (named_fact && !it->second.weak)  // "spacecraft" or "engine" alone suggests nothing
        for (const auto& c : candidates(it->second, kNoRole, phrase))
          if (fields.insert(c.field).second) cands.push_back(c);
    }
  }
  if (cands.size() != 1 || numbers != 1 || !number) return "";
  if (cands[0].exhaust) return "";
  const Field field = cands[0].field == Field::Tof && bounded ? Field::TofMax : cands[0].field;
  return suggestion(field, *number, cands[0].dim);
}

}  // namespace helios::spec::detail
